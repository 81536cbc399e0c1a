# Shared by the shell tests run by tests/run.sh: run_case NAME FUNCTION runs FUNCTION in a
# subshell with set -e, prints cmocka-style "[ RUN      ]" / "[       OK ]" / "[  FAILED  ]" lines
# (the case's last output line on success, its whole log on failure) and counts failures in
# $fails, and its wall seconds after the name (make test's time budget is kept case by case).
# The caller sets T (a scratch folder) and ends with: exit $((fails != 0))
fails=0
run_case() { # name, function
  local t0=$EPOCHREALTIME rc=0 sec
  echo "[ RUN      ] $1"
  # a plain command: as part of `||` or `if`, bash would ignore set -e inside the case (every
  # command but the last could fail unnoticed)
  ( set -e; "$2" ) >"$T/case.log" 2>&1
  rc=$?
  sec=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')
  if [[ $rc -eq 0 ]]; then tail -1 "$T/case.log"; echo "[       OK ] $1 ($sec s)"
  else cat "$T/case.log"; echo "[  FAILED  ] $1 ($sec s)"; fails=$((fails + 1)); fi
}

skip_case() { # name, reason: a case that cannot run here, as cmocka prints one (tests/run.sh counts
  # a case by its RUN line: a SKIPPED line alone would count as a failure taken back)
  echo "[ RUN      ] $1"
  echo "$1: skipped, $2"
  echo "[  SKIPPED ] $1"
}

# Shared by the shell tests run by tests/run.sh: run_case NAME FUNCTION runs FUNCTION in a
# subshell with set -e, prints cmocka-style "[ RUN      ]" / "[       OK ]" / "[  FAILED  ]" lines
# (the case's last output line on success, its whole log on failure) and counts failures in
# $fails. The caller sets T (a scratch folder) and ends with: exit $((fails != 0))
fails=0
run_case() { # name, function
  echo "[ RUN      ] $1"
  ( set -e; "$2" ) >"$T/case.log" 2>&1
  if [[ $? -eq 0 ]]; then tail -1 "$T/case.log"; echo "[       OK ] $1"
  else cat "$T/case.log"; echo "[  FAILED  ] $1"; fails=$((fails + 1)); fi
}

#!/usr/bin/env bash
# vlt_make.sh MDIR PREFIX [MAKE ARGUMENTS...]: compiles and links a model that `verilator --cc --exe`
# (without --build) wrote to MDIR as two translation units: PREFIX__fast.cpp includes the classes
# Verilator lists as its fast path (the evaluation of every cycle), PREFIX__slow.cpp those it lists
# as slow (constructors, the initial and settle evaluation, run once), so that the make arguments can
# compile them at different levels (OPT_FAST, OPT_SLOW). Verilator's one-unit build
# (VM_PARALLEL_BUILDS=0) compiles both at OPT_FAST; its parallel build compiles each of its files on
# its own, parsing verilated.h and the model's headers again for each (about 1 s of CPU a file).
set -eu
d=$1 p=$2
shift 2
# the classes of a list: Verilator's class list file, read by make
classes() { make -s -C "$d" -f "${p}_classes.mk" --no-print-directory --eval "saarcor_print: ; @echo \$($1) \$($2)" saarcor_print; }
unity() { # NAME CLASS-LIST SUPPORT-LIST: PREFIX__NAME.cpp, rewritten only when its list changed
  local out="$d/${p}__$1.cpp"
  for f in $(classes "$2" "$3"); do echo "#include \"$f.cpp\""; done >"$out.tmp"
  if cmp -s "$out.tmp" "$out"; then rm "$out.tmp"; else mv "$out.tmp" "$out"; fi
}
unity fast VM_CLASSES_FAST VM_SUPPORT_FAST
unity slow VM_CLASSES_SLOW VM_SUPPORT_SLOW
exec make -s -C "$d" -f "$p.mk" --no-print-directory VM_PARALLEL_BUILDS=1 VM_FAST="${p}__fast" VM_SLOW="${p}__slow" "$@"

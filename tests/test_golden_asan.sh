#!/usr/bin/env bash
# The golden-image testbench (tests/test_golden.sh) with the program built with AddressSanitizer
# + UndefinedBehaviorSanitizer (build/asan/saarcor, make BUILD=build/asan SAN=1): render,
# reference and compare of each case run sanitized, and every image must still equal the golden
# one bit for bit. Any sanitizer report fails the case (tests/run.sh sets halt_on_error and
# exitcode=99; LeakSanitizer is on). The integer-arithmetic check (4) is left to the plain run:
# it compares another program. Cases: SAARCOR_GOLDEN_CASES; by default a subset that keeps
# make test within its time budget: the generated cornell, room and animated (t = 1.5) scenes,
# the bunny glTF file (the loader path), and the emissive and vertex_colours scenes (texture,
# emission and vertex-colour paths of the shader). Left out: terrain, plants and truck (about 25-40 s each
# sanitized) and gallery (503k triangles: about 8 minutes sanitized); all eight pass
# (SAARCOR_GOLDEN_CASES="cornell room plants terrain animated truck bunny gallery", 12 minutes on
# 2 shared cores). Prints cmocka-style lines (golden_asan_NAME) for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
ASAN_BIN=${SAARCOR_ASAN_BIN:-build/asan/saarcor}
[[ -x $ASAN_BIN ]] || { echo "test_golden_asan: $ASAN_BIN is missing (make BUILD=build/asan SAN=1 build/asan/saarcor)"; exit 1; }
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:exitcode=99:malloc_context_size=8:quarantine_size_mb=32} # as tests/run.sh
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export SAARCOR_GOLDEN_CASES=${SAARCOR_GOLDEN_CASES:-cornell room animated bunny emissive vertex_colours}
SAARCOR_BIN=$ASAN_BIN SAARCOR_HW_BIN= SAARCOR_GOLDEN_PREFIX=golden_asan_ exec bash tests/test_golden.sh

# saarcor top-level Makefile.
#   make            build build/saarcor (fp24 format e7m16)
#   make run        install missing Debian packages, build, run the default job
#   make test       install missing packages, build, run all tests (+ sanitizer build of the unit tests),
#                   each as soon as its builds are done, the longest first, as many at a time as there
#                   are cores (tests/run.sh)
#   make asan       build and run the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer
#   make verify-fp  fp24 verification against MPFR: 10^7 random vectors per op and width, exhaustive unary
#   make bench      all benchmarks -> build/bench/ (bench-fp: fp24 throughput; bench-build: kd-tree and
#                   memory-image build against Embree; bench-render: primary rays against Embree;
#                   bench-accuracy: fp24 images and hits against the double-precision reference;
#                   bench-cycle: the cycle model beside the paper's Tables 3 and 4, sweeps, simulator speed;
#                   bench-longrun: peak RSS over 1,000 frames of the animated scene)
#   make widths     build build/w/<format>/saarcor for every tested fp24 format
#   make rtl-test   Verilator co-simulation of rtl/ against the C model (operators at 6 formats with
#                   10^6 vectors each, units (also the rebase unit and the transformation unit's wide
#                   mode) on random and captured vectors; the list unit, the caches with the memory
#                   port, the thread scheduler, the traversal unit, the RGS's ray generation and the
#                   tile controller on cycle-mode frames of room, terrain, plants; ray generation on
#                   an orthographic frame and random blocks; the ray tracing core on every packet of
#                   functional frames of cornell, room, subpass_scene_opaque.glb; those frames at
#                   128x96 through the Verilated DynRTP, render --mode rtl, beside --mode cycle), lint
#   make rtl        the Verilated DynRTP (rtl/dynrtp.sv) that saarcor render --mode rtl runs
#   make synth      Yosys synthesis figures -> docs/synth.md
#   make bench-precision  every format against the binary64 reference: time, cycles, PSNR, plots
#   make results    docs/results.md from build/bench/ (run after make bench)
#   make mpi        build/libsaarcor_mpi.so, the MPI distributor render --mpi and jobs --mpi load
#   make bench-mpi  render --mpi with 1 and 2 worker ranks on localhost -> build/bench/mpi.md, mpi.json
#   make fuzz       libFuzzer harnesses of tests/fuzz/ (glTF loader, memory image + device model, command
#                   line), FUZZ_SECONDS (default 60) each -> build/fuzz/ (crashes in build/fuzz/crashes/)
#   make stress     numerical stability stress suite at every width and with the robust edge option
#                   (make robust) -> build/bench/stress.md, stress.json
# Variables: BUILD (output folder), SAN=1 (sanitizers), V=1 (show commands), VERIFY_N,
#   SIM_ARITH=fast|hw: arithmetic of the simulator's units (default fast: the host fast path of
#   tb/fp/f24_fast.h; hw: the integer hardware reference; the same bits, make test checks it).

SHELL := /bin/bash
.DEFAULT_GOAL := all
.DELETE_ON_ERROR:
.SECONDARY:

BUILD ?= build
MPICC := $(shell command -v mpicc 2>/dev/null)
CC := gcc
CXX := g++
SAN ?= 0
V ?= 0
Q := $(if $(filter 1,$(V)),,@)

# fp24 formats: e<E>m<M>. The default is the paper's 1+7+16 = 24 bits.
DEFAULT_FMT := e7m16
FORMATS := e7m8 e7m10 e7m12 e7m14 e7m16 e7m18 e7m20 e7m23 e8m23
fmt_flags = -DF24_EXP_BITS=$(word 1,$(subst m, ,$(subst e,,$(1)))) -DF24_MAN_BITS=$(word 2,$(subst m, ,$(subst e,,$(1))))

VERSION := 0.1.0+$(shell git describe --always --dirty 2>/dev/null || echo unknown)

# -Wno-psabi: GCC notes, at every use of the fast path's vector values as a parameter, that their
# passing changed in GCC 4.6: the functions are static inline, no ABI boundary is crossed
WARN := -Wall -Wextra -Werror -Wshadow -Wno-unused-label -Wno-psabi
# Under the sanitizers (SAN=1, make test's ASan build) everything at -O1, the level ASan is made
# for: make test's ASan build and its tests took 255 + 111 s of CPU with the simulator at -O3 and
# 149 + 138 s at -O1 (fresh clone, 2026-11-30; its renders as fast: test_golden_asan 24 against 23 s)
OPT := $(if $(filter 1,$(SAN)),-O1,-O2)
# the simulator's objects (SIM_SRCS: units, memory image, cycle model, reference, command line;
# the fp24 arithmetic's: hls/fp24, tb/fp) at
# -O3: its loop unswitching, peeling and vectorization take 6.8% of a functional render's
# instructions (room 256x192 primary, callgrind: 22,729 -> 21,180 Ir/px; images bit-identical, as
# -ffp-contract=off keeps every binary64 rounding). OPT on the command line (make test's -O0
# build) leaves them at its level, and the SIM_ARITH=hw build (the reference, not timed) stays at
# -O2, which saves make test 6 s of CPU a build.
SIM_OPT := $(if $(filter command line,$(origin OPT))$(filter hw,$(SIM_ARITH))$(filter 1,$(SAN)),,-O3)
SAN_ON := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
SANFLAGS := $(if $(filter 1,$(SAN)),$(SAN_ON))
# no fused multiply-add: the fast fp24 path relies on one binary64 rounding per operation
# CFG_FLAGS: hls/config.h settings of this build folder (e.g. the robust edge option, make robust)
CFG_FLAGS ?=
# DBG: the debug information, line tables by default: backtraces, sanitizer reports, perf and
# callgrind keep their file:line, and compiling takes 20-35% less CPU than with -g (gltf_load.o
# 5.8 -> 4.2 s, isect_unit.o under ASan 7.0 -> 4.6 s; make test compiles about 1000 objects);
# make DBG=-g for variables and types in a debugger (in its own BUILD folder: make does not
# rebuild objects for changed flags)
DBG ?= -g1
CFLAGS := -std=c11 $(WARN) $(OPT) $(DBG) -ffp-contract=off -fno-math-errno $(SANFLAGS) $(CFG_FLAGS) -MMD -MP
CXXFLAGS := -std=c++17 $(WARN) $(OPT) $(DBG) $(SANFLAGS) -MMD -MP
INCLUDES := -Ihls -Ihls/fp24 -Ihls/units -Ihost/fp24 -Itb/fp -Itb/ref -Itb/cycle -Itb/cli -Ihost/image -Ihost/scene -Ihost/kdtree -Ihost/memimage -Iscenes -Itb/mpi
LDLIBS := -lmpfr -lgmp -ltinygltf -lpng -lOpenEXRCore-3_1 -lOpenImageIO -lOpenImageIO_Util -lstdc++ -lm -ldl
TEST_LDLIBS := -lcmocka $(LDLIBS)

# ---- sources -------------------------------------------------------------------------------
HLS_FP24 := $(sort $(wildcard hls/fp24/*.c))
TB_FP := $(sort $(wildcard tb/fp/*.c))
# render --capture-unit-io records the units' calls through linker wrappers (tb/cli/capture.c) in
# the program's capture build (CAPTURE_DIR beside it: build/capture/saarcor, build/w/FMT/capture/saarcor:
# the same objects with capture.c and --wrap), which the program runs for it; the program itself has
# neither, so that no render pays a wrapper per unit call (room 512x384, 1 thread: 5% of the time)
CAPTURE_SRC := tb/cli/capture.c
CAPTURE_DIR := capture
CLI := $(filter-out $(CAPTURE_SRC),$(sort $(wildcard tb/cli/*.c)))
HOST_CXX := $(sort $(wildcard host/*/*.cpp))
HOST_C := $(sort $(filter-out host/memimage/%,$(wildcard host/*/*.c scenes/*.c)))
# the double-precision reference renderer (tb/ref) calls the memory image only for the camera;
# tb/ref/ref_units.c is the brute-force closest hit with the units' arithmetic (tests, stress)
REF := $(sort $(wildcard tb/ref/*.c))
MEMIMAGE := $(sort $(wildcard host/memimage/*.c))
HLS_UNITS := $(sort $(wildcard hls/units/*.c))
CYCLE := $(sort $(wildcard tb/cycle/*.c))
# faster simulation versions of unit functions (the rays of a packet as vector lanes), compiled
# with the units' flags: the fast build takes them, the hardware-arithmetic one compiles them empty
SIM_UNITS := $(sort $(wildcard tb/sim/*.c))

# the simulator (units, memory image, reference, command line) computes fp24 with the host fast
# path unless SIM_ARITH=hw; hls/fp24 and tb/fp always hold the integer reference
SIM_ARITH ?= fast
# the fast path's header is named by the build (hls/ names nothing of tb/): tb/fp/f24_fast.h maps
# f24_add ... onto it. The packet values' functions are built for AVX2 and the baseline, chosen at
# load time; SIM_LANES=baseline builds only the baseline version (what machines without AVX2 run),
# which tests/test_sim_arith.sh checks too
SIM_LANES ?= clones
CFLAGS += $(if $(filter baseline,$(SIM_LANES)),-DF24_SIM_BASELINE)
FAST_SIM_FLAGS := -DF24_FAST_SIM -DF24_SIM_HEADER='"f24_fast.h"'
SIM_FLAGS := $(if $(filter fast,$(SIM_ARITH)),$(FAST_SIM_FLAGS),$(if $(filter hw,$(SIM_ARITH)),,$(error SIM_ARITH must be fast or hw)))
SIM_SRCS = $(MEMIMAGE) $(HLS_UNITS) $(SIM_UNITS) $(CYCLE) $(REF) $(CLI) $(CAPTURE_SRC)

comma := ,
CAPTURE_WRAP := $(addprefix -Wl$(comma)--wrap=,xform_point xform_vector isect_unit_rebased isect_unit_packet trav_node_split_held \
  list_unit_entry list_mailboxes_clear mem_iface_read mem_iface_flush mem_iface_new_frame rgs_block_begin \
  rebase_origin xform_point_wide xform_vector_wide xform_enter_rays rebase_rays \
  trav_scene_clip trav_object_clip trav_start trav_walk trace_begin trace_step shade_rec_normals \
  rgs_sample_bilinear rgs_surface_frame rgs_light_packet rgs_lerp rgs_lerp_normal rgs_light_colour rgs_add_light \
  rgs_spawn_children rgs_surface_at rgs_surfaces rgs_accumulate_ray rgs_accumulate_rays)

# per-format objects: everything that depends on the fp24 parameters
fp_objs = $(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(HLS_FP24) $(TB_FP))
fmt_objs = $(call fp_objs,$(1)) $(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(MEMIMAGE) $(HLS_UNITS) $(SIM_UNITS) $(CYCLE) $(REF))
# HOST_BUILD: where the host objects (loader, kd-trees, images; neither number format nor
# SIM_ARITH nor CFG_FLAGS changes them) are taken from; make test's hw and robust builds share
# those of the main build instead of compiling the C++ loader again
HOST_BUILD ?= $(BUILD)
HOST_OBJS := $(patsubst %.cpp,$(HOST_BUILD)/obj/host/%.o,$(HOST_CXX)) $(patsubst %.c,$(HOST_BUILD)/obj/host/%.o,$(HOST_C))
# The saarcor program loads OpenImageIO's shim on first use from libsaarcor_img.so next to it
# (host/image/img.c: its ~260 libraries would cost every command ~0.2 s of start-up); the tests,
# benchmarks and fuzzers link it in, and so does the sanitizer build's program (LeakSanitizer
# can fault scanning the dynamic TLS of libraries loaded after start: "Tracer caught signal 11").
IMG_OBJ := $(HOST_BUILD)/obj/host/host/image/img_oiio.o
IMG_LIB := $(HOST_BUILD)/libsaarcor_img.so
IMG_LIBS := -lOpenImageIO -lOpenImageIO_Util
PROG_HOST_OBJS := $(if $(filter 1,$(SAN)),$(HOST_OBJS),$(filter-out $(IMG_OBJ),$(HOST_OBJS)))
PROG_LDLIBS := $(if $(filter 1,$(SAN)),$(LDLIBS),$(filter-out $(IMG_LIBS),$(LDLIBS)))
$(foreach d,$(sort $(BUILD) $(HOST_BUILD)),$(d)/obj/host/host/image/img_oiio.o): CXXFLAGS += -fPIC
# Under ASan the glTF shims (tinygltf's JSON templates) compile at -O0: at -O2 the instrumented
# template code took 10x the CPU (gltf_write.o 57 against 6 s, make test's ASan build 34 s of
# its 190), for parsers that run milliseconds in the tests; every check stays on
ifeq ($(SAN),1)
$(addprefix $(HOST_BUILD)/obj/host/,$(patsubst %.cpp,%.o,$(filter host/scene/gltf_%,$(HOST_CXX)))): CXXFLAGS += -O0
endif
# The kd-tree builder at -O3 too: its unrolled and vectorized loops save 6.6% of the bottom-level
# build's instructions (bunny.glb, callgrind, 1 CPU: kd_build_many 2.038 -> 1.903 G Ir); the trees
# are the same bits at any level (-ffp-contract=off; scripts/kd_identical.sh). Not SIM_OPT: the
# SIM_ARITH=hw build shares HOST_BUILD's object, and rebuilding it there at -O2 (after an edit of
# kdtree.c) left build/saarcor's next link with the slower builder (bunny: 1.739 -> 1.862 G Ir).
KD_OPT := $(if $(filter command line,$(origin OPT))$(filter 1,$(SAN)),,-O3)
$(foreach d,$(sort $(BUILD) $(HOST_BUILD)),$(d)/obj/host/host/kdtree/kdtree.o): CFLAGS += $(KD_OPT)
$(IMG_LIB): $(IMG_OBJ)
	@echo "  LD    $@"
	$(Q)$(CXX) $(SANFLAGS) -shared $< -o $@ $(IMG_LIBS)

define HOST_RULES
$(1)/obj/host/%.o: %.cpp
	@mkdir -p $$(@D)
	@echo "  CXX   $$@"
	$(Q)$$(CXX) $$(CXXFLAGS) $$(INCLUDES) -c $$< -o $$@

$(1)/obj/host/%.o: %.c
	@mkdir -p $$(@D)
	@echo "  CC    $$@"
	$(Q)$$(CC) $$(CFLAGS) $$(INCLUDES) -c $$< -o $$@
endef
$(foreach d,$(sort $(BUILD) $(HOST_BUILD)),$(eval $(call HOST_RULES,$(d))))

# tests built and run at every number format
FORMAT_TESTS := test_f24 test_f24_select test_f24_record test_f24_sum

# C objects of format $(1) in folder $(2): $(BUILD)/obj/<format> (the simulator's with SIM_FLAGS) and
# $(BUILD)/obj/hw/<format> (the units in the hardware arithmetic, for the RTL benches: rtl_c_objs)
define FORMAT_CC
$(2)/%.o: %.c
	@mkdir -p $$(@D)
	@echo "  CC    $$@"
	$(Q)$$(CC) $$(CFLAGS) $(call fmt_flags,$(1)) $$(INCLUDES) -I$(BUILD) -c $$< -o $$@
endef
$(foreach f,$(FORMATS),$(eval $(call FORMAT_CC,$(f),$(BUILD)/obj/$(f))) $(eval $(call FORMAT_CC,$(f),$(BUILD)/obj/hw/$(f))))

define FORMAT_RULES
$(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(SIM_SRCS)): CFLAGS += $(SIM_FLAGS)
$(call fp_objs,$(1)) $(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(SIM_SRCS)): CFLAGS += $(SIM_OPT)

$(BUILD)/w/$(1)/saarcor: $(call fmt_objs,$(1)) $(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(CLI)) $(PROG_HOST_OBJS) | $(IMG_LIB) $(BUILD)/w/$(1)/$(CAPTURE_DIR)/saarcor
	@mkdir -p $$(@D)
	@echo "  LD    $$@"
	$(Q)$$(CC) $$(SANFLAGS) $$^ -o $$@ $$(PROG_LDLIBS)

$(BUILD)/w/$(1)/$(CAPTURE_DIR)/saarcor: $(call fmt_objs,$(1)) $(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(CLI) $(CAPTURE_SRC)) $(PROG_HOST_OBJS) | $(IMG_LIB)
	@mkdir -p $$(@D)
	@echo "  LD    $$@"
	$(Q)$$(CC) $$(SANFLAGS) $$^ -o $$@ $$(CAPTURE_WRAP) $$(PROG_LDLIBS)

$(foreach t,$(FORMAT_TESTS),$(BUILD)/w/$(1)/$(t)): $(BUILD)/w/$(1)/%: $(BUILD)/obj/$(1)/tests/%.o $(call fp_objs,$(1))
	@mkdir -p $$(@D)
	@echo "  LD    $$@"
	$(Q)$$(CC) $$(SANFLAGS) $$^ -o $$@ $$(TEST_LDLIBS)
endef
$(foreach f,$(FORMATS),$(eval $(call FORMAT_RULES,$(f))))

# the host tests, benchmarks and fuzz replays link the simulator's units: they see their state
# (trace_state, its held packet values: hls/fp24/f24_held.h) as the units were compiled
$(BUILD)/obj/host/tests/%.o: CFLAGS += $(SIM_FLAGS)

# tests find tests/golden and other inputs from the source tree
$(BUILD)/obj/%/tests/test_f24.o $(BUILD)/obj/host/tests/%.o: CFLAGS += -DSAARCOR_SRC_DIR='"$(CURDIR)"'

# the selection test is compiled with the build-time switch that maps f24_* onto the fast path
$(BUILD)/obj/%/tests/test_f24_select.o: CFLAGS += $(FAST_SIM_FLAGS)

# the version string lives in a generated header that changes only when the version does
$(BUILD)/version.h: FORCE
	@mkdir -p $(@D)
	@echo '#define SAARCOR_VERSION "$(VERSION)"' > $@.tmp
	@cmp -s $@.tmp $@ && rm $@.tmp || mv $@.tmp $@
FORCE:
$(foreach f,$(FORMATS),$(BUILD)/obj/$(f)/tb/cli/cmd_version.o): $(BUILD)/version.h

$(BUILD)/saarcor: $(BUILD)/w/$(DEFAULT_FMT)/saarcor | $(BUILD)/$(CAPTURE_DIR)/saarcor
	cp $< $@
$(BUILD)/$(CAPTURE_DIR)/saarcor: $(BUILD)/w/$(DEFAULT_FMT)/$(CAPTURE_DIR)/saarcor
	@mkdir -p $(@D)
	cp $< $@

# host module tests: tests/test_<module>.c linked with all host objects (default fp24 format)
HOST_TESTS := $(patsubst tests/%.c,$(BUILD)/%,$(filter-out $(patsubst %,tests/%.c,$(FORMAT_TESTS)),$(wildcard tests/test_*.c)))
$(BUILD)/test_%: $(BUILD)/obj/host/tests/test_%.o $(HOST_OBJS) $(call fmt_objs,$(DEFAULT_FMT))
	@echo "  LD    $@"
	$(Q)$(CC) $(SANFLAGS) $^ -o $@ $(TEST_LDLIBS)


.PHONY: fuzz fuzz-build fuzz-replay all mpi bench-mpi widths deps run test unit-tests test-programs asan verify-fp hls-check hls-vectors bench bench-skip bench-longrun bench-fp bench-build bench-render bench-accuracy bench-cycle bench-precision bench-peers results robust stress rtl rtl-lint rtl-test synth synth-dynrtp check-full clean
all: $(BUILD)/saarcor $(BUILD)/w/e8m23/saarcor $(if $(MPICC),$(BUILD)/libsaarcor_mpi.so)

# ---- MPI: the work distributor that `render --mpi` and `jobs --mpi` dlopen (docs/mpi.md) -------
# the only part linked with libmpi; build/saarcor runs without Open MPI installed
mpi: $(BUILD)/libsaarcor_mpi.so
$(BUILD)/libsaarcor_mpi.so: tb/mpi/saarcor_mpi.c tb/mpi/saarcor_mpi.h
	@mkdir -p $(@D)
	@echo "  MPICC $@"
	$(Q)$(if $(MPICC),mpicc,$(error make mpi needs mpicc: install libopenmpi-dev (make deps))) -std=c11 $(WARN) $(OPT) $(DBG) $(SANFLAGS) -fPIC -shared -Itb/mpi $< -o $@
widths: $(foreach f,$(FORMATS),$(BUILD)/w/$(f)/saarcor)

deps:
	@bash scripts/install-deps.sh

# generate the default scene, show what the host makes of it, render it through the units
DEFAULT_SCENE := room
run: deps
	@$(MAKE) --no-print-directory all
	$(BUILD)/saarcor gen $(DEFAULT_SCENE) -o $(BUILD)/$(DEFAULT_SCENE).glb
	$(BUILD)/saarcor info $(BUILD)/$(DEFAULT_SCENE).glb --validate
	$(BUILD)/saarcor render $(BUILD)/$(DEFAULT_SCENE).glb -o $(BUILD)/$(DEFAULT_SCENE).png --width 1024 --height 768

# ---- tests ---------------------------------------------------------------------------------
UNIT_TESTS := $(foreach f,$(FORMATS),$(addprefix $(BUILD)/w/$(f)/,$(FORMAT_TESTS))) $(HOST_TESTS)
# make test runs the unit tests under ASan/UBSan at the narrowest, the default and the widest
# format (width-dependent undefined behaviour lives at the edges); make asan at every format
ASAN_TEST_FORMATS := e7m8 $(DEFAULT_FMT) e8m23
ASAN_UNIT_TESTS := $(foreach f,$(ASAN_TEST_FORMATS),$(addprefix build/asan/w/$(f)/,$(FORMAT_TESTS))) \
	$(patsubst $(BUILD)/%,build/asan/%,$(HOST_TESTS))
test-programs: $(UNIT_TESTS) $(BUILD)/saarcor

# unit tests of this build folder (used with BUILD=build/asan SAN=1 by `make asan`)
unit-tests: test-programs
	@bash tests/run.sh --report $(BUILD)/test-report.txt $(UNIT_TESTS)

asan:
	@$(MAKE) --no-print-directory BUILD=build/asan SAN=1 unit-tests

# tests/test_memcheck.sh: on CPUs without RDTSCP, valgrind needs this preload (see the source)
$(BUILD)/valgrind/hwy_timer_shim.so: tests/valgrind/hwy_timer_shim.c
	@mkdir -p $(@D)
	@echo "  CC    $@"
	$(Q)$(CC) -shared -fPIC -O2 $(WARN) $< -o $@

# tests/test_determinism.sh compares the program built with -O0 (only the program: a small cost)
O0_BUILD := $(BUILD)/O0

# make test's builds (all of them alone: make test-builds; make test makes each one a prerequisite
# of the test programs that need it, below): sub-makes of one make, so the two cores stay busy
# across what were eight phases one after another (326 s of wall time for 545 s of CPU). The hw, baseline and robust programs take the main build's host
# objects (HOST_BUILD), so they wait for those; the RTL models link the main build's objects
# (build/obj/<format>), so their make follows the main one; the ASan build and its fuzz replays
# are another make.
# The fp32 program: tests/test_mpi.sh's jobs of two formats (not built under ASan, whose build of
# the simulator at a second format cost make test 25 s and was run by no test).
# The RTL models of make test: the DynRTP first (the longest build: make starts it first), whose
# frame (tests/test_rtl_render.sh) checks every block of the RGS's controllers and every packet of
# the core; tb_rgs_ctrl, the controllers' own bench on more blocks, is make rtl-test's.
TEST_RTL_BENCHES := dynrtp f24_ops units sum list cache sched rgs wide trav core shade fifo
.PHONY: test-builds test-build-host test-build-main test-build-rtl test-build-asan test-build-hw test-build-baseline test-build-robust test-build-O0
test-builds: test-build-asan test-build-main test-build-rtl test-build-hw test-build-baseline test-build-robust test-build-O0
test-build-host:
	@$(MAKE) --no-print-directory $(HOST_OBJS) $(IMG_LIB)
test-build-main: test-build-host
	@$(MAKE) --no-print-directory test-programs $(BUILD)/w/e8m23/saarcor mpi $(BUILD)/valgrind/hwy_timer_shim.so
# after the main build: the models link its objects (build/obj/<format>), which two makes at once
# would both write
test-build-rtl: test-build-main
	@$(MAKE) --no-print-directory $(addprefix $(BUILD)/rtl/$(DEFAULT_FMT)/tb_,$(TEST_RTL_BENCHES))
test-build-asan:
	@$(MAKE) --no-print-directory BUILD=build/asan SAN=1 FORMATS="$(ASAN_TEST_FORMATS)" test-programs fuzz-replay
test-build-hw: test-build-host
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/hw HOST_BUILD=$(BUILD) SIM_ARITH=hw $(BUILD)/hw/saarcor
test-build-baseline: test-build-host
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/baseline HOST_BUILD=$(BUILD) SIM_LANES=baseline $(BUILD)/baseline/saarcor
test-build-robust: test-build-host
	@$(MAKE) --no-print-directory robust
test-build-O0:
	@$(MAKE) --no-print-directory BUILD=$(O0_BUILD) OPT=-O0 $(O0_BUILD)/saarcor

# make test: the builds and the test programs in one make graph, so that no core waits: each
# program (tests/run.sh --one) starts as soon as the builds it needs are done, beside the builds
# still running (the RTL models, the ASan build), the longest first; the totals at the end
# (tests/run.sh --collect). Before, all builds and then all tests: 10.7 min of wall time on the
# 2-core machine for 9.2 min of both cores' CPU.
TEST_SHELL := tests/test_sim_arith.sh tests/test_rtl.sh tests/test_golden.sh tests/test_cli.sh tests/test_rtl_render.sh \
  tests/test_interrupt.sh tests/test_hls.sh tests/test_memcheck.sh tests/test_mpi.sh tests/test_golden_asan.sh \
  tests/test_heatmap.sh tests/test_determinism.sh tests/test_stress.sh tests/test_limits.sh tests/test_longrun.sh \
  tests/test_vcd.sh tests/test_fuzz.sh tests/test_hits.sh tests/test_shading.sh
TEST_PROGS = $(TEST_SHELL) $(UNIT_TESTS) $(ASAN_UNIT_TESTS)
TEST_RUNS := $(BUILD)/test-runs
test_run = $(TEST_RUNS)/$(subst /,__,$(1)).done
# what each program needs built (the builds are sub-makes: a program waits for the whole of its own)
$(foreach p,$(TEST_SHELL) $(UNIT_TESTS),$(call test_run,$(p))): test-build-main
$(foreach p,tests/test_golden_asan.sh tests/test_fuzz.sh $(ASAN_UNIT_TESTS),$(call test_run,$(p))): test-build-asan
$(call test_run,tests/test_sim_arith.sh): test-build-hw test-build-baseline
$(call test_run,tests/test_golden.sh): test-build-hw
$(call test_run,tests/test_rtl.sh) $(call test_run,tests/test_rtl_render.sh): test-build-rtl
$(call test_run,tests/test_determinism.sh): test-build-O0
$(call test_run,tests/test_stress.sh): test-build-robust
$(TEST_RUNS)/%.done:
	@bash tests/run.sh --one $(TEST_RUNS) $(subst __,/,$*)
	@touch $@

test: deps
	@rm -rf $(TEST_RUNS)
	@$(MAKE) --no-print-directory -j$$(nproc) $(foreach p,$(TEST_PROGS),$(call test_run,$(p)))
	@bash tests/run.sh --collect $(TEST_RUNS) --report $(BUILD)/test-report.txt $(TEST_PROGS)

# ---- fuzzing: libFuzzer harnesses of tests/fuzz/ (tests/fuzz/README.md) ----------------------------
# Everything is compiled again with clang, ASan, UBSan and the fuzzer's coverage instrumentation
# into build/fuzz/ (tb/cli/main.c with main renamed, for fuzz_cli). make fuzz runs each harness
# for FUZZ_SECONDS from the seed corpus (build/fuzz/corpus/, made by tests/fuzz/corpus.sh) and the
# regression inputs (tests/fuzz/regress/); make test runs those inputs once (tests/test_fuzz.sh).
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_SECONDS ?= 60
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CFLAGS := -O1 -g -Wall -Wextra -Werror -Wno-unused-label $(FUZZ_SAN) -fsanitize=fuzzer-no-link -ffp-contract=off \
  $(call fmt_flags,$(DEFAULT_FMT)) $(INCLUDES) -Itests -I$(BUILD) -MMD -MP
FUZZ_TARGETS := $(patsubst tests/fuzz/%.c,$(FUZZ_DIR)/%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_OBJS := $(patsubst %.c,$(FUZZ_DIR)/obj/%.o,$(HLS_FP24) $(TB_FP) $(SIM_SRCS) $(HOST_C)) \
  $(patsubst %.cpp,$(FUZZ_DIR)/obj/%.o,$(HOST_CXX))
$(patsubst %.c,$(FUZZ_DIR)/obj/%.o,$(SIM_SRCS)): FUZZ_EXTRA := $(SIM_FLAGS)
$(FUZZ_DIR)/obj/tb/cli/main.o: FUZZ_EXTRA += -Dmain=saarcor_main
$(FUZZ_DIR)/obj/tb/cli/cmd_version.o: $(BUILD)/version.h

$(FUZZ_DIR)/obj/%.o: %.c
	@mkdir -p $(@D)
	@echo "  FUZZCC $@"
	$(Q)clang -std=c11 $(FUZZ_CFLAGS) $(FUZZ_EXTRA) -c $< -o $@

$(FUZZ_DIR)/obj/%.o: %.cpp
	@mkdir -p $(@D)
	@echo "  FUZZCXX $@"
	$(Q)clang++ -std=c++17 $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_TARGETS): $(FUZZ_DIR)/%: $(FUZZ_DIR)/obj/tests/fuzz/%.o $(FUZZ_OBJS)
	@echo "  LD    $@"
	$(Q)clang++ $(FUZZ_SAN) -fsanitize=fuzzer $^ -o $@ $(CAPTURE_WRAP) $(LDLIBS) -lpthread

$(FUZZ_DIR)/corpus/.stamp: $(BUILD)/saarcor tests/fuzz/corpus.sh tests/fuzz/bundle.py tests/fuzz/cli_seeds.txt
	@bash tests/fuzz/corpus.sh $(BUILD)/saarcor $(FUZZ_DIR)/corpus
	@touch $@

fuzz-build: $(FUZZ_TARGETS) $(FUZZ_DIR)/corpus/.stamp

# make test's regression run of the same harnesses (tests/test_fuzz.sh): linked with a main that
# replays input files (tests/fuzz/replay_main.c) and this build's objects (build/asan: ASan+UBSan),
# so no clang build of everything is needed; the seed corpus as for make fuzz
REPLAY_DIR := $(BUILD)/fuzz-replay
REPLAY_TARGETS := $(patsubst tests/fuzz/%.c,$(REPLAY_DIR)/%,$(wildcard tests/fuzz/fuzz_*.c))
REPLAY_CLI := $(filter-out $(BUILD)/obj/$(DEFAULT_FMT)/tb/cli/main.o,$(patsubst %.c,$(BUILD)/obj/$(DEFAULT_FMT)/%.o,$(CLI) $(CAPTURE_SRC)))
$(BUILD)/obj/host/tests/fuzz/%.o: CFLAGS += -Itests
$(REPLAY_DIR)/cli_main.o: tb/cli/main.c $(BUILD)/version.h
	@mkdir -p $(@D)
	@echo "  CC    $@"
	$(Q)$(CC) $(CFLAGS) $(SIM_FLAGS) $(INCLUDES) -I$(BUILD) -Dmain=saarcor_main -c $< -o $@
$(REPLAY_DIR)/fuzz_cli: $(REPLAY_DIR)/cli_main.o $(REPLAY_CLI)
$(REPLAY_DIR)/fuzz_cli: REPLAY_WRAP := $(CAPTURE_WRAP)
$(REPLAY_TARGETS): $(REPLAY_DIR)/%: $(BUILD)/obj/host/tests/fuzz/%.o $(BUILD)/obj/host/tests/fuzz/replay_main.o $(HOST_OBJS) $(call fmt_objs,$(DEFAULT_FMT))
	@mkdir -p $(@D)
	@echo "  LD    $@"
	$(Q)$(CXX) $(SANFLAGS) $^ -o $@ $(REPLAY_WRAP) $(LDLIBS) -lpthread
$(REPLAY_DIR)/corpus/.stamp: $(BUILD)/saarcor tests/fuzz/corpus.sh tests/fuzz/bundle.py tests/fuzz/cli_seeds.txt
	@bash tests/fuzz/corpus.sh $(BUILD)/saarcor $(REPLAY_DIR)/corpus
	@touch $@
fuzz-replay: $(REPLAY_TARGETS) $(REPLAY_DIR)/corpus/.stamp

fuzz: deps
	@$(MAKE) --no-print-directory -j$$(nproc) fuzz-build
	@bash tests/fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# ---- HLS readiness: hls/ alone in the synthesizable subset, per configuration -------------------
# make hls-check: the general design and every hls/config_NAME.h; CONFIG=NAME: that one only
HLS_CONFIGS := $(patsubst hls/config_%.h,%,$(wildcard hls/config_*.h))
hls-check:
	@python3 scripts/hls_summary.py $(if $(CONFIG),$(CONFIG),default $(HLS_CONFIGS))

# test vectors for tb/vitis/run.tcl (the ones tests/test_hls.sh makes): captured unit
# transactions of the room, and the cornell memory image with the simulator's image of it
hls-vectors: $(BUILD)/saarcor
	@mkdir -p $(BUILD)/hls-vectors
	$(BUILD)/saarcor render room --width 64 --height 48 --capture-unit-io $(BUILD)/hls-vectors/cap --capture-limit 20000 -o $(BUILD)/hls-vectors/room.png >/dev/null
	$(BUILD)/saarcor info cornell --width 64 --height 48 --image $(BUILD)/hls-vectors/cornell.bin >/dev/null
	$(BUILD)/saarcor render cornell --width 64 --height 48 -o $(BUILD)/hls-vectors/cornell.ppm >/dev/null

# ---- RTL: Verilator co-simulation against the C model, lint, synthesis -------------------------
RTL := $(sort $(wildcard rtl/*.sv))
RTL_FORMATS := e7m8 e7m12 e7m16 e7m20 e7m23 e8m23
# The models' C++ at -O1: as fast to run as Verilator's default -Os (tb_core: 1.29 against 1.35 s
# on a 32x24 frame) and about a fifth quicker to compile; compiled by clang++, which takes a fifth
# less CPU than g++ at -O1 for a model that runs a third faster (tb_core: 59 against 76 s of
# compilation, 0.52 against 0.77 s on the cornell 32x24 capture); the Verilator run-time library
# (verilated.cpp, verilated_threads.cpp: 4 s of compilation) is compiled once into
# $(BUILD)/rtl/verilated/ and linked into every model instead of once per model (VM_GLOBAL_FAST=).
# A model's C++ is compiled as two translation units (scripts/vlt_make.sh): its fast path (the
# evaluation of every cycle) at -O1, its slow part (constructors, initial and settle evaluation, run
# once; a third of a model's C++) at -O0, which takes a quarter of the CPU of -O1 there (the DynRTP's
# slow part 58 -> 13 s, its cornell 32x24 frame as fast: 9.8 against 10.2 s). Each of Verilator's
# 10-200 files compiled on its own parsed verilated.h and the model's headers again, about 1 s of
# CPU per file at -O1, most of a large model's compilation: one unit for the whole took make test's
# 12 models 346 -> 145 s of CPU (tb_rgs_ctrl 84 -> 32, tb_shade 80 -> 32, tb_core 64 -> 28), their
# benches as fast (tb_core on cornell 32x24 0.50 s both ways). make -j2 over the models keeps both
# cores busy (make test's order or the largest first: the same wall time, 112 against 114 s).
VLT_CXX := clang++
VERILATOR_FLAGS := --cc --exe -Wall -Wno-fatal -O2 --x-assign fast --x-initial fast
VLT_MAKE_ARGS := -j 2 OPT_FAST=-O1 OPT_SLOW=-O0 OPT_GLOBAL=-O1 VM_GLOBAL_FAST= CXX=$(VLT_CXX) LINK=$(VLT_CXX)
VLT_INCLUDE := $(shell verilator --getenv VERILATOR_ROOT 2>/dev/null)/include
VLT_RUNTIME := $(BUILD)/rtl/verilated/verilated.o $(BUILD)/rtl/verilated/verilated_threads.o
$(BUILD)/rtl/verilated/%.o: $(VLT_INCLUDE)/%.cpp
	@mkdir -p $(@D)
	@echo "  CXX $@"
	$(Q)$(VLT_CXX) -O1 -faligned-new -fcf-protection=none -w -DVM_COVERAGE=0 -DVM_SC=0 -DVM_TRACE=0 -DVM_TRACE_FST=0 \
	  -DVM_TRACE_VCD=0 -I$(VLT_INCLUDE) -I$(VLT_INCLUDE)/vltstd -c $< -o $@
# the units in the hardware arithmetic (SIM_ARITH=hw): the benches read their state (the traversal's
# held intervals and rays, hls/fp24/f24_held.h) as the fp24 words the RTL holds
rtl_c_objs = $(call fp_objs,$(1)) $(patsubst %.c,$(BUILD)/obj/hw/$(1)/%.o,$(HLS_UNITS))
fmt_e = $(word 1,$(subst m, ,$(subst e,,$(1))))
fmt_m = $(word 2,$(subst m, ,$(subst e,,$(1))))

# build/rtl/<format>/tb_<name>: the Verilator model of rtl/tb/tb_<name>.sv with its C++ bench,
# linked with the C model of the same format; rtl/tb/tb_<name>.vlt, where there is one, is its
# Verilator configuration (tb_dynrtp's: the units' ports its per-unit checks read).
# build/rtl/<format>/b<N>/tb_dynrtp: the DynRTP with N threads and N block controllers (-GTHREADS=N
# -GRGS_BLOCKS=N; the default model's are 32 and 8), which render --mode rtl --threads-per-pipe N runs
# (tb/cli/render_rtl.c); dynrtp_params gives a DynRTP model's threads and block controllers to
# Verilator and to its harness.
# One recipe for both: the model in $(@D), its bench from its name, RTL_FMT and RTL_PARAMS per rule
rtl_tb = $(patsubst tb_%,%,$(notdir $@))
dynrtp_params = -GTHREADS=$(1) -GRGS_BLOCKS=$(2) -CFLAGS -DTB_THREADS=$(1) -CFLAGS -DTB_RGS_BLOCKS=$(2)
define RTL_MODEL
@mkdir -p $(@D)
@echo "  VERILATOR $@"
$(Q)verilator $(VERILATOR_FLAGS) -GE=$(call fmt_e,$(RTL_FMT)) -GM=$(call fmt_m,$(RTL_FMT)) $(RTL_PARAMS) --top-module tb_$(rtl_tb) \
  -Mdir $(@D)/obj_$(rtl_tb) -o $(CURDIR)/$@ $(addprefix $(CURDIR)/,$(RTL)) \
  $(CURDIR)/rtl/tb/tb_$(rtl_tb).sv $(CURDIR)/rtl/tb/tb_$(rtl_tb).cpp $(wildcard $(CURDIR)/rtl/tb/tb_$(rtl_tb).vlt) \
  -CFLAGS "$(call fmt_flags,$(RTL_FMT)) $(addprefix -I$(CURDIR)/,hls hls/fp24 hls/units host/fp24 tb/fp host/memimage host/kdtree host/scene)" \
  -LDFLAGS "$(addprefix $(CURDIR)/,$(call rtl_c_objs,$(RTL_FMT)) $(VLT_RUNTIME)) -lmpfr -lgmp -lm" >$(@D)/build_$(rtl_tb).log 2>&1 \
  && bash scripts/vlt_make.sh $(@D)/obj_$(rtl_tb) Vtb_$(rtl_tb) $(VLT_MAKE_ARGS) >>$(@D)/build_$(rtl_tb).log 2>&1 \
  || { tail -30 $(@D)/build_$(rtl_tb).log; exit 1; }
endef
# a model's prerequisites: format $(1), bench $(2)
rtl_deps = rtl/tb/tb_$(2).sv rtl/tb/tb_$(2).cpp $(wildcard rtl/tb/*.h rtl/tb/*.vlt) $(RTL) $(call rtl_c_objs,$(1)) $(VLT_RUNTIME)
define RTL_RULES
$(BUILD)/rtl/$(1)/%: RTL_FMT := $(1)
$(BUILD)/rtl/$(1)/tb_%: $(call rtl_deps,$(1),%)
	$$(RTL_MODEL)
$(BUILD)/rtl/$(1)/tb_dynrtp: RTL_PARAMS = $(call dynrtp_params,32,8)
$(BUILD)/rtl/$(1)/b%/tb_dynrtp: RTL_PARAMS = $$(call dynrtp_params,$$*,$$*)
$(BUILD)/rtl/$(1)/b%/tb_dynrtp: $(call rtl_deps,$(1),dynrtp)
	$$(RTL_MODEL)
endef
$(foreach f,$(RTL_FORMATS),$(eval $(call RTL_RULES,$(f))))

# make rtl: the Verilated DynRTP (rtl/dynrtp.sv) with its harness, which saarcor render --mode rtl
# runs (build/rtl/<format>/tb_dynrtp beside build/saarcor; another format: make widths and
# make build/rtl/e8m23/tb_dynrtp for render --precision fp32 --mode rtl)
rtl: $(BUILD)/saarcor $(BUILD)/rtl/$(DEFAULT_FMT)/tb_dynrtp

RTL_N ?= 1000000
rtl-lint:
	@for m in $(notdir $(basename $(RTL))); do verilator --lint-only -Wall $(RTL) --top-module $$m || exit 1; done
	@echo "rtl-lint: verilator --lint-only -Wall clean for $(words $(RTL)) modules"

# every operator at every format: edge set + RTL_N random vectors per operation class (+ golden hex);
# the square root and the integer conversion on every encoding where W <= 24 (16.8 M at e7m16, ~25 s)
rtl-test: deps rtl-lint
	@$(MAKE) --no-print-directory all $(foreach f,$(RTL_FORMATS),$(BUILD)/rtl/$(f)/tb_f24_ops $(BUILD)/rtl/$(f)/tb_units $(BUILD)/rtl/$(f)/tb_sum \
	  $(BUILD)/rtl/$(f)/tb_rgs $(BUILD)/rtl/$(f)/tb_wide $(BUILD)/rtl/$(f)/tb_shade $(BUILD)/rtl/$(f)/tb_accum) \
	  $(foreach f,$(DEFAULT_FMT) e8m23,$(BUILD)/rtl/$(f)/tb_surface $(BUILD)/rtl/$(f)/tb_rgs_ctrl $(BUILD)/rtl/$(f)/tb_list $(BUILD)/rtl/$(f)/tb_cache $(BUILD)/rtl/$(f)/tb_sched $(BUILD)/rtl/$(f)/tb_trav $(BUILD)/rtl/$(f)/tb_core) \
	  $(BUILD)/rtl/$(DEFAULT_FMT)/tb_dynrtp $(BUILD)/rtl/$(DEFAULT_FMT)/tb_fifo
	@# sync_fifo's two storages (LUT RAM, block RAM) against a deque, every output every cycle
	@$(BUILD)/rtl/$(DEFAULT_FMT)/tb_fifo -n $(RTL_N) | tee $(BUILD)/rtl/fifo.log
	@mkdir -p $(BUILD)/rtl/capture
	@set -o pipefail; for f in $(RTL_FORMATS); do \
	  extra=; [ $$f = $(DEFAULT_FMT) ] && extra=$$(ls tests/golden/f24/{add,sub,mul,div,lt,le,eq,min,max,sqrt,to_i32}.hex); \
	  em=$${f#e}; [ $$(( $${em%m*} + $${em#*m} )) -lt 24 ] && extra="$$extra --unary-all"; \
	  $(BUILD)/rtl/$$f/tb_f24_ops -n $(RTL_N) $$extra || exit 1; done | tee $(BUILD)/rtl/ops.log
	@set -o pipefail; for s in room terrain plants; do \
	  for f in $(DEFAULT_FMT) e8m23; do \
	    $(BUILD)/w/$$f/saarcor render $$s -o $(BUILD)/rtl/$$s.$$f.png --width 128 --height 96 \
	      --capture-unit-io $(BUILD)/rtl/capture/$$s.$$f --capture-limit 200000 >/dev/null || exit 1; \
	    $(BUILD)/rtl/$$f/tb_units -n 0 --capture $(BUILD)/rtl/capture/$$s.$$f || exit 1; \
	    $(BUILD)/rtl/$$f/tb_wide -n 0 --capture $(BUILD)/rtl/capture/$$s.$$f || exit 1; done; done | tee $(BUILD)/rtl/units.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_units -n $(RTL_N) || exit 1; done \
	  | tee -a $(BUILD)/rtl/units.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_wide -n $(RTL_N) || exit 1; done \
	  | tee -a $(BUILD)/rtl/units.log
	@# list unit, memory interface, scheduler, traversal unit, ray generation: a cycle-mode frame at the paper's 64 threads per pipe
	@set -o pipefail; for s in room terrain plants; do \
	  for f in $(DEFAULT_FMT) e8m23; do \
	    $(BUILD)/w/$$f/saarcor render $$s -o $(BUILD)/rtl/$$s.$$f.cycle.png --width 128 --height 96 --mode cycle \
	      --threads-per-pipe 64 --capture-unit-io $(BUILD)/rtl/capture/$$s.$$f.cycle --capture-limit 1000000 >/dev/null || exit 1; \
	    $(BUILD)/rtl/$$f/tb_list -n $$(( $(RTL_N) / 10 )) --capture $(BUILD)/rtl/capture/$$s.$$f.cycle || exit 1; \
	    $(BUILD)/rtl/$$f/tb_cache --capture $(BUILD)/rtl/capture/$$s.$$f.cycle || exit 1; \
	    $(BUILD)/rtl/$$f/tb_sched -n $(RTL_N) --capture $(BUILD)/rtl/capture/$$s.$$f.cycle || exit 1; \
	    $(BUILD)/rtl/$$f/tb_rgs -n 0 --capture $(BUILD)/rtl/capture/$$s.$$f.cycle --order 16 || exit 1; \
	    $(BUILD)/rtl/$$f/tb_trav -n $$(( $(RTL_N) / 10 )) --capture $(BUILD)/rtl/capture/$$s.$$f.cycle || exit 1; \
	  done; done | tee $(BUILD)/rtl/memory.log
	@mkdir -p $(BUILD)/rtl/animated
	@set -o pipefail; $(BUILD)/saarcor render animated -o $(BUILD)/rtl/animated/a.png --width 128 --height 96 --mode cycle \
	  --threads-per-pipe 64 --frames 0:3 --capture-unit-io $(BUILD)/rtl/capture/animated.cycle --capture-limit 1000000 >/dev/null \
	  && { $(BUILD)/rtl/$(DEFAULT_FMT)/tb_list -n 0 --capture $(BUILD)/rtl/capture/animated.cycle \
	  && $(BUILD)/rtl/$(DEFAULT_FMT)/tb_cache --capture $(BUILD)/rtl/capture/animated.cycle \
	  && $(BUILD)/rtl/$(DEFAULT_FMT)/tb_sched -n 0 --capture $(BUILD)/rtl/capture/animated.cycle \
	  && $(BUILD)/rtl/$(DEFAULT_FMT)/tb_rgs -n 0 --capture $(BUILD)/rtl/capture/animated.cycle --order 16 \
	  && $(BUILD)/rtl/$(DEFAULT_FMT)/tb_trav -n 0 --capture $(BUILD)/rtl/capture/animated.cycle; } | tee -a $(BUILD)/rtl/memory.log
	@# the ray tracing core: every packet of functional frames (128x96) with shadows and reflections
	@set -o pipefail; for s in cornell room ../shared/scenes/subpass_scene_opaque.glb; do \
	  for f in $(DEFAULT_FMT) e8m23; do n=$$(basename $$s .glb); \
	    $(BUILD)/w/$$f/saarcor render $$s -o $(BUILD)/rtl/core.$$n.$$f.png --width 128 --height 96 \
	      --capture-unit-io $(BUILD)/rtl/capture/core.$$n.$$f --capture-limit 1000000 >/dev/null || exit 1; \
	    $(BUILD)/rtl/$$f/tb_core --capture $(BUILD)/rtl/capture/core.$$n.$$f || exit 1; \
	  done; done | tee $(BUILD)/rtl/core.log
	@# render --mode rtl: frames (128x96, shadows and secondary rays) through the Verilated DynRTP, bit for bit
	@# functional mode's PNG and primary hits; the RTL's cycles beside cycle mode's with the same parameters
	@set -o pipefail; for s in cornell room ../shared/scenes/subpass_scene_opaque.glb; do n=$$(basename $$s .glb); \
	  $(BUILD)/saarcor render $$s -o $(BUILD)/rtl/frame.$$n.rtl.png --aov $(BUILD)/rtl/frame.$$n.rtl.exr --width 128 --height 96 \
	    --mode rtl --stats $(BUILD)/rtl/frame.$$n.rtl.json || exit 1; \
	  $(BUILD)/saarcor render $$s -o $(BUILD)/rtl/frame.$$n.f.png --aov $(BUILD)/rtl/frame.$$n.f.exr --width 128 --height 96 >/dev/null || exit 1; \
	  $(BUILD)/saarcor render $$s -o $(BUILD)/rtl/frame.$$n.c.png --width 128 --height 96 --mode cycle \
	    --stats $(BUILD)/rtl/frame.$$n.c.json >/dev/null || exit 1; \
	  cmp $(BUILD)/rtl/frame.$$n.rtl.png $(BUILD)/rtl/frame.$$n.f.png || exit 1; \
	  oiiotool $(BUILD)/rtl/frame.$$n.f.exr --ch t,N.X,N.Y,N.Z,node,triangle,u,v -o $(BUILD)/rtl/frame.$$n.f8.exr || exit 1; \
	  idiff -fail 0 -warn 0 $(BUILD)/rtl/frame.$$n.f8.exr $(BUILD)/rtl/frame.$$n.rtl.exr >/dev/null || exit 1; \
	  python3 -c "import json, sys; r, c = (json.load(open(p))['cycle']['cycles'] for p in sys.argv[1:]); \
	    print('$$n 128x96: rtl %d cycles, cycle mode %d, ratio %.2f' % (r, c, r / c))" \
	    $(BUILD)/rtl/frame.$$n.rtl.json $(BUILD)/rtl/frame.$$n.c.json; done | tee $(BUILD)/rtl/frame.log
	@# the RGS's ray generation: an orthographic frame (the cornell box's camera made orthographic), random blocks
	@$(BUILD)/saarcor gen cornell -o $(BUILD)/rtl/capture/cornell.gltf >/dev/null
	@python3 scripts/ortho_camera.py $(BUILD)/rtl/capture/cornell.gltf $(BUILD)/rtl/capture/ortho.gltf
	@set -o pipefail; for f in $(DEFAULT_FMT) e8m23; do \
	  $(BUILD)/w/$$f/saarcor render $(BUILD)/rtl/capture/ortho.gltf -o $(BUILD)/rtl/ortho.$$f.png --width 128 --height 96 \
	    --mode cycle --capture-unit-io $(BUILD)/rtl/capture/ortho.$$f.cycle --capture-limit 4000 >/dev/null || exit 1; \
	  $(BUILD)/rtl/$$f/tb_rgs -n 0 --capture $(BUILD)/rtl/capture/ortho.$$f.cycle --order 16 || exit 1; done | tee $(BUILD)/rtl/rgs.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_rgs -n $(RTL_N) || exit 1; done | tee -a $(BUILD)/rtl/rgs.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_sum -n $(RTL_N) || exit 1; done \
	  | tee -a $(BUILD)/rtl/units.log
	@# the RGS's shading datapath: the vertex normals decoded and the textures sampled in frames with
	@# shadows and reflections (textured scenes from ../shared/scenes when present), random ones
	@set -o pipefail; for s in room cornell plants $(wildcard ../shared/scenes/subpass_scene_opaque.glb ../shared/scenes/CesiumMilkTruck.glb \
	  ../shared/scenes/Avocado/Avocado.gltf); do \
	  for f in $(DEFAULT_FMT) e8m23; do \
	    $(BUILD)/w/$$f/saarcor render $$s -o $(BUILD)/rtl/shade.$$f.png --width 128 --height 96 \
	      --capture-unit-io $(BUILD)/rtl/capture/shade.$$f --capture-limit 1000000 >/dev/null 2>&1 || exit 1; \
	    $(BUILD)/rtl/$$f/tb_shade -n 0 --capture $(BUILD)/rtl/capture/shade.$$f || exit 1; done; done | tee $(BUILD)/rtl/shade.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_shade -n $(RTL_N) || exit 1; done \
	  | tee -a $(BUILD)/rtl/shade.log
	@# the RGS's surface at a hit (rgs_surface) and the accumulation (rgs_accum): every surface and ray of 128x96 frames with shadows and reflections
	@set -o pipefail; for s in room cornell vertex_colours emissive uv_transform unlit $(wildcard ../shared/scenes/subpass_scene_opaque.glb \
	  ../shared/scenes/CesiumMilkTruck.glb); do \
	  for f in $(DEFAULT_FMT) e8m23; do \
	    $(BUILD)/w/$$f/saarcor render $$s -o $(BUILD)/rtl/surface.$$f.png --width 128 --height 96 --max-depth 2 \
	      --capture-unit-io $(BUILD)/rtl/capture/surface.$$f --capture-limit 1000000 >/dev/null 2>&1 || exit 1; \
	    $(BUILD)/rtl/$$f/tb_surface -n 20000 --capture $(BUILD)/rtl/capture/surface.$$f || exit 1; \
	    $(BUILD)/rtl/$$f/tb_accum -n 0 --capture $(BUILD)/rtl/capture/surface.$$f || exit 1; done; done \
	  | tee $(BUILD)/rtl/surface.log
	@set -o pipefail; for f in $(RTL_FORMATS); do $(BUILD)/rtl/$$f/tb_accum -n $(RTL_N) || exit 1; done \
	  | tee -a $(BUILD)/rtl/surface.log
	@# the RGS's per-block control (rgs_ctrl): every block of frames with shadows and reflections, depth 3
	@set -o pipefail; for s in cornell:128x96 room:64x48 vertex_colours:64x48 emissive:64x48 \
	  $(addsuffix :128x96,$(wildcard ../shared/scenes/subpass_scene_opaque.glb ../shared/scenes/CesiumMilkTruck.glb)); do \
	  for f in $(DEFAULT_FMT) e8m23; do sz=$${s##*:}; \
	    $(BUILD)/w/$$f/saarcor render $${s%:*} -o $(BUILD)/rtl/ctrl.$$f.png --width $${sz%x*} --height $${sz#*x} \
	      --capture-unit-io $(BUILD)/rtl/capture/ctrl.$$f --capture-limit 10 >/dev/null 2>&1 || exit 1; \
	    $(BUILD)/rtl/$$f/tb_rgs_ctrl --capture $(BUILD)/rtl/capture/ctrl.$$f --max-depth 3 || exit 1; done; done \
	  | tee $(BUILD)/rtl/rgs_ctrl.log
	@# the short form with every mutant (make test builds the rounder's alone)
	@SAARCOR_RTL_MUTANTS=all BUILD=$(BUILD) bash tests/run.sh tests/test_rtl.sh tests/test_rtl_render.sh

# Yosys synthesis of every module (synth_xilinx; synth_ice40 + nextpnr-ice40 for the operators;
# the operators and the intersection unit across mantissa widths) -> docs/synth.md
synth: deps
	python3 scripts/synth.py

# only the whole DynRTP at the paper's configuration (7-series and iCE40, over an hour each), merged
# into build/synth/synth.json ("dynrtp") and docs/synth.md
synth-dynrtp: deps
	python3 scripts/synth.py --dynrtp

# the long checks make test leaves out: every RTL bench at every format with the 128x96 frames through
# the Verilated DynRTP (rtl-test), and the synthesis of every module and of the whole DynRTP (synth)
check-full: test rtl-test synth

# ---- verification and benchmarks -----------------------------------------------------------
VERIFY_N ?= 10000000
verify-fp: deps
	@$(MAKE) --no-print-directory -j$$(nproc) widths
	@bash tests/verify_fp.sh $(BUILD) $(VERIFY_N) $(FORMATS)

bench-fp: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench_fp
	@mkdir -p $(BUILD)/bench
	valgrind --tool=callgrind --callgrind-out-file=$(BUILD)/bench/fp.callgrind $(BUILD)/bench_fp --count 2>/dev/null
	callgrind_annotate --inclusive=yes $(BUILD)/bench/fp.callgrind > $(BUILD)/bench/fp.callgrind.txt
	$(BUILD)/bench_fp --json $(BUILD)/bench/fp.json --markdown $(BUILD)/bench/fp.md \
	  --instructions $(BUILD)/bench/fp.callgrind.txt
	@cat $(BUILD)/bench/fp.md

# host build benchmark: kd-trees and memory image against Embree's BVH build
bench-build: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench_build $(BUILD)/saarcor
	@mkdir -p $(BUILD)/bench
	$(BUILD)/bench_build --out $(BUILD)/bench --saarcor $(BUILD)/saarcor
	@cat $(BUILD)/bench/build.md

$(BUILD)/bench_build: $(BUILD)/obj/host/tests/bench/bench_build.o $(BUILD)/obj/host/tests/bench/embree_scene.o $(HOST_OBJS) $(call fmt_objs,$(DEFAULT_FMT))
	@echo "  LD    $@"
	$(Q)$(CC) $(SANFLAGS) $^ -o $@ $(LDLIBS) -lembree3

# the Embree harness and our side's timing, shared by bench-render and bench-peers (one meaning of
# "ours / Embree"); our frame is the render command's own render_region
BENCH_HARNESS := $(addprefix $(BUILD)/obj/host/tests/bench/,embree_scene.o bench_units.o) \
	$(addprefix $(BUILD)/obj/$(DEFAULT_FMT)/tb/cli/,render_region.o interrupt.o)

# primary rays at 1024x768: the units (functional) against Embree on the same rays
bench-render: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench_render
	@mkdir -p $(BUILD)/bench
	$(BUILD)/bench_render --out $(BUILD)/bench
	@cat $(BUILD)/bench/render.md

$(BUILD)/bench_render: $(BUILD)/obj/host/tests/bench/bench_render.o $(BENCH_HARNESS) $(HOST_OBJS) $(call fmt_objs,$(DEFAULT_FMT))
	@echo "  LD    $@"
	$(Q)$(CC) $(SANFLAGS) $^ -o $@ $(LDLIBS) -lembree3

# fp24 images against the double-precision reference at 1024x768 (after bench-render: Embree beside)
bench-accuracy: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p $(BUILD)/bench
	python3 tests/bench/bench_accuracy.py --out $(BUILD)/bench

# the cycle model at 512x384 and 1024x768 beside the paper, thread and pipe sweeps, simulator speed
# (runs bench_render for Embree in the same run)
bench-cycle: deps
	@$(MAKE) --no-print-directory all $(BUILD)/bench_render
	@mkdir -p $(BUILD)/bench
	python3 tests/bench/bench_cycle.py --out $(BUILD)/bench

bench-skip: deps
	@$(MAKE) --no-print-directory all
	python3 tests/bench/bench_skip.py --out $(BUILD)/bench

# the robust edge option (hls/config.h SAARCOR_CFG_EDGE_EPS, docs/stress.md) in its own build folder
ROBUST_EDGE_EPS := 8
robust:
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/robust HOST_BUILD=$(BUILD) CFG_FLAGS=-DSAARCOR_CFG_EDGE_EPS=$(ROBUST_EDGE_EPS) $(BUILD)/robust/saarcor

# the numerical stability stress suite at every width and with the robust option -> build/bench/stress.md
stress: deps
	@$(MAKE) --no-print-directory -j$$(nproc) widths robust
	python3 tests/bench/bench_stress.py --out $(BUILD)/bench

# every format against the binary64 reference: run time, cycles, PSNR, hits (after stress and synth
# for the leak and area columns, if their results exist) -> build/bench/precision.md
bench-precision: deps
	@$(MAKE) --no-print-directory -j$$(nproc) all widths
	python3 tests/bench/bench_precision.py --out $(BUILD)/bench

# peers on the same primary rays: Embree single rays and packets (1, 2 threads), our functional
# mode trace only (1, 2 threads) and with shading (render_region, 1 thread), our cycle mode, the
# traversal unit's algorithms (render --traversal) -> build/bench/peers.md
bench-peers: deps
	@$(MAKE) --no-print-directory all $(BUILD)/bench_peers
	@mkdir -p $(BUILD)/bench
	$(BUILD)/bench_peers --out $(BUILD)/bench
	python3 tests/bench/bench_peers.py --out $(BUILD)/bench

$(BUILD)/bench_peers: $(BUILD)/obj/host/tests/bench/bench_peers.o $(BENCH_HARNESS) $(HOST_OBJS) $(call fmt_objs,$(DEFAULT_FMT))
	@echo "  LD    $@"
	$(Q)$(CC) $(SANFLAGS) $^ -o $@ $(LDLIBS) -lembree3 -lpthread

# render --mpi from 1 to 2 worker ranks on localhost: wall time, speedup, communication -> build/bench/mpi.md
bench-mpi: deps
	@$(MAKE) --no-print-directory all mpi
	@mkdir -p $(BUILD)/bench
	python3 tests/bench/bench_mpi.py --out $(BUILD)/bench

# memory over 1,000 frames of the animated scene, functional and cycle mode: RSS and peak RSS
# after frames 10 and 1000 -> build/bench/longrun.md, longrun.json
bench-longrun: deps
	@$(MAKE) --no-print-directory $(BUILD)/saarcor
	@mkdir -p $(BUILD)/bench
	python3 tests/bench/bench_longrun.py --out $(BUILD)/bench

# docs/results.md from the reports in build/bench/ (each row with machine, command, date)
results:
	python3 scripts/results.py

bench: bench-fp bench-build bench-render bench-accuracy bench-cycle bench-skip stress bench-precision bench-peers bench-longrun bench-mpi
	@$(MAKE) --no-print-directory results

$(BUILD)/bench_fp: $(BUILD)/obj/$(DEFAULT_FMT)/tests/bench/bench_fp.o $(call fp_objs,$(DEFAULT_FMT))
	@echo "  LD    $@"
	$(Q)$(CC) $^ -o $@ $(LDLIBS)

clean:
	rm -rf build

-include $(shell find $(BUILD)/obj $(FUZZ_DIR)/obj -name '*.d' 2>/dev/null)

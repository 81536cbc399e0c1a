# Vitis HLS flow for the saarcor top functions (docs/hls.md): C simulation, C synthesis and C/RTL
# co-simulation of xform_top, isect_top, trav_top and dynrtc_top, with the testbenches and vectors
# of `make test` (tb/vitis/tb_units.c on captured unit transactions, tb/vitis/tb_dynrtc.c on a
# memory image and the simulator's image of it).
#
#   make hls-vectors                                 # writes build/hls-vectors/ (needs build/saarcor)
#   vitis_hls -f tb/vitis/run.tcl [-tclargs PART [CONFIG [STEPS]]]
#
# PART    the FPGA part (default xcvu9p-flga2104-2-i, any part Vitis knows)
# CONFIG  a hls/config_NAME.h scene configuration, or "default" for the general design
# STEPS   any of csim,csynth,cosim (default: all three)
# Run from the repository root. Each top function gets its own solution in build/vitis/<top>.

set part "xcvu9p-flga2104-2-i"
set config "default"
set steps "csim,csynth,cosim"
if {[info exists argv]} {
    if {[llength $argv] > 0} { set part [lindex $argv 0] }
    if {[llength $argv] > 1} { set config [lindex $argv 1] }
    if {[llength $argv] > 2} { set steps [lindex $argv 2] }
}
set root [pwd]
set vectors "$root/build/hls-vectors"
if {![file exists "$vectors/cap/xform.hex"]} {
    puts "run.tcl: $vectors is missing: run `make hls-vectors` first"
    exit 1
}
set cflags "-I$root/hls -I$root/hls/fp24 -I$root/hls/units -I$root/hls/top"
if {$config ne "default"} { append cflags " -include $root/hls/config_$config.h" }
set sources [concat [glob $root/hls/fp24/*.c] [glob $root/hls/units/*.c] [glob $root/hls/top/*.c]]

# top function -> {testbench, testbench arguments}; 11.1 ns = the prototype's 90 MHz
set tops [dict create \
    xform_top  [list tb_units.c  "$vectors/cap"] \
    isect_top  [list tb_units.c  "$vectors/cap"] \
    trav_top   [list tb_units.c  "$vectors/cap"] \
    dynrtc_top [list tb_dynrtc.c "$vectors/cornell.bin $vectors/cornell.ppm 3 1"]]

dict for {top spec} $tops {
    lassign $spec tb tbargs
    open_project -reset "build/vitis/$top"
    set_top $top
    foreach src $sources { add_files $src -cflags $cflags }
    add_files -tb "$root/tb/vitis/$tb" -cflags $cflags
    open_solution -reset "solution_$config" -flow_target vivado
    set_part $part
    create_clock -period 11.1 -name default
    if {[string match "*csim*" $steps]} { csim_design -argv $tbargs }
    if {[string match "*csynth*" $steps]} { csynth_design }
    if {[string match "*cosim*" $steps]} { cosim_design -argv $tbargs -rtl verilog }
    close_project
}
exit 0

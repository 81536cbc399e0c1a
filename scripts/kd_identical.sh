#!/bin/bash
# Are two builds' kd-trees bit-identical? Compares the memory images (saarcor info SCENE --image)
# that two saarcor binaries write for the scenes of make bench-build (tests/bench/bench_build.c:
# the shared glTF scenes and the generators), each on 1 CPU and on all CPUs the shell may use, by
# md5. The image holds every object's tree (nodes, split planes, leaf lists), so a builder change
# that keeps the default trees must leave every line "same". This is how the exact builder's
# speed-ups were checked (issue 19); it is a tool, not part of make test (about a minute each).
#
# usage: scripts/kd_identical.sh OLD_SAARCOR NEW_SAARCOR [SCENES_DIR]
#        (SCENES_DIR defaults to ../shared/scenes beside the source tree)
# exit:  0 all images identical, 1 some differ or a build failed, 2 usage
set -u
if [ $# -lt 2 ] || [ ! -x "$1" ] || [ ! -x "$2" ]; then
    echo "usage: $0 OLD_SAARCOR NEW_SAARCOR [SCENES_DIR]" >&2
    exit 2
fi
old=$1 new=$2
src=$(cd "$(dirname "$0")/.." && pwd)
scenes=${3:-$src/../shared/scenes}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
all_cpus=$(taskset -pc $$ | sed 's/.*: //')
first_cpu=${all_cpus%%[-,]*}

# md5 of the image PROGRAM builds for SCENE on CPUS, or "failed"
image_md5() {
    local prog=$1 scene=$2 cpus=$3 mem=()
    # the 500k-triangle gallery does not fit the default 24 MB (bench-build builds it with 1 GB)
    case $scene in *gallery_ccby_503k.glb) mem=(--mem-mb 64) ;; esac
    if taskset -c "$cpus" nice -n 10 "$prog" info "$scene" "${mem[@]}" --image "$tmp/img" >/dev/null 2>&1; then
        md5sum <"$tmp/img" | cut -c1-32
    else
        echo failed
    fi
}

status=0
for scene in Box.glb CesiumMilkTruck.glb teapot.glb primitives.glb subpass_scene_opaque.glb bunny.glb \
    bunny_instanced16.glb gallery_ccby_503k.glb cornell room plants terrain animated; do
    path=$scene
    case $scene in *.glb) path=$scenes/$scene ;; esac
    for cpus in "$first_cpu" "$all_cpus"; do
        a=$(image_md5 "$old" "$path" "$cpus")
        b=$(image_md5 "$new" "$path" "$cpus")
        verdict=same
        if [ "$a" = failed ] || [ "$a" != "$b" ]; then
            verdict=DIFFERENT
            status=1
        fi
        printf '%-26s cpus %-5s %s %s %s\n' "$scene" "$cpus" "$a" "$b" "$verdict"
    done
done
exit $status

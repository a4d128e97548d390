#!/usr/bin/env bash
# Gathers the seed inputs of every fuzz target into OUT_DIR/<target>/ (emptied first): the
# project's own seeds (fuzz/corpus/<target>/), its test data (tests/data/), its built-in models
# and problems (data/) and, when present, the third-party data in ../shared/data (read in place,
# never copied into the repository). Seeds larger than the target's limit are skipped, and at
# most kMaxSeeds per source pattern are taken (the smallest first: they run fastest). awk, not
# head, takes them: head would end the pipe early and kill sort with SIGPIPE under pipefail.
#
# Usage: fuzz/seed-corpus.sh OUT_DIR
set -euo pipefail

out_dir=${1:?usage: fuzz/seed-corpus.sh OUT_DIR}
repo=$(cd "$(dirname "$0")/.." && pwd)
shared="$repo/../shared/data"
readonly kMaxSeeds=60
readonly kTextLimit=$((64 * 1024))
readonly kMeshLimit=$((256 * 1024))

# add_files TARGET SIZE_LIMIT DIR FIND_ARGS...: the matching files of DIR (if it exists).
add_files() {
  local target=$1 limit=$2 dir=$3
  shift 3
  [ -d "$dir" ] || return 0
  mkdir -p "$out_dir/$target"
  find "$dir" -type f "$@" -size -"$((limit + 1))"c -printf '%s %p\n' | sort -n |
    awk -v n="$kMaxSeeds" 'NR <= n' | while read -r _ file; do
      local name=${file#"$dir"/}
      cp "$file" "$out_dir/$target/$(basename "$dir")_${name//\//_}"
    done
}

# add_moveit_pair SCENE REQUEST NAME: one moveit_problem input (see fuzz/fuzz_inputs.hpp).
add_moveit_pair() {
  mkdir -p "$out_dir/moveit_problem"
  { cat "$1"; printf '\n#--- request ---\n'; cat "$2"; } >"$out_dir/moveit_problem/$3"
}

rm -rf "$out_dir"
mkdir -p "$out_dir"
if [ ! -d "$shared" ]; then
  echo "fuzz seeds: ../shared/data is absent; seeds from the repository only" >&2
fi

for own in "$repo"/fuzz/corpus/*/; do
  add_files "$(basename "$own")" "$kMeshLimit" "${own%/}"
done

add_files urdf "$kTextLimit" "$repo/data" -name '*.urdf'
add_files urdf "$kTextLimit" "$shared" -name '*.urdf'
add_files srdf "$kTextLimit" "$repo/data" -name '*.srdf'
add_files xacro "$kTextLimit" "$shared" -name '*.xacro'
add_files joint_limits "$kTextLimit" "$repo/data" -name '*.joint_limits.yaml'
add_files joint_limits "$kTextLimit" "$shared" -name 'joint_limits.yaml'
add_files kautham_problem "$kTextLimit" "$repo/data/problems" -name '*.xml'
add_files kautham_problem "$kTextLimit" "$shared/kautham" -name '*.xml'
add_files kautham_controls "$kTextLimit" "$repo/data" -name '*.cntr'
add_files kautham_controls "$kTextLimit" "$shared/kautham" -name '*.cntr'
add_files kautham_benchmark "$kTextLimit" "$shared/kautham" -name 'benchmark*.xml'
add_files instruction_corpus "$kTextLimit" "$repo/data/corpus" -name '*.tsv'
# One seed per corpus instruction (at most kMaxSeeds): the instruction target reads plain text.
mkdir -p "$out_dir/instruction"
awk -F '\t' -v n="$kMaxSeeds" -v out="$out_dir/instruction" \
  '!/^#/ && NF == 3 && count < n { file = out "/corpus_" NR; printf "%s", $3 > file; close(file); count++ }' \
  "$repo/data/corpus/instructions.tsv"
for format in stl obj dae ply iv wrl; do
  add_files "mesh_$format" "$kMeshLimit" "$repo/tests/data/meshes" -iname "*.$format"
  add_files "mesh_$format" "$kMeshLimit" "$shared" -iname "*.$format"
done

moveit="$repo/tests/data/moveit"
for scene in "$moveit"/*scene*.yaml "$moveit"/bad_[!r]*.yaml; do
  add_moveit_pair "$scene" "$moveit/good_request.yaml" "tests_$(basename "$scene")"
done
for request in "$moveit"/*request*.yaml; do
  add_moveit_pair "$moveit/good_scene.yaml" "$request" "tests_$(basename "$request")"
done
if [ -d "$shared/mbm/panda" ]; then
  for family in "$shared"/mbm/panda/*/; do
    for scene in "$family"scene000[1-3].yaml; do
      [ -f "$scene" ] || continue
      request="${scene%/scene*}/request${scene##*/scene}"
      add_moveit_pair "$scene" "$request" "mbm_$(basename "$family")_$(basename "$scene")"
    done
  done
fi

for target_dir in "$out_dir"/*/; do
  printf 'fuzz seeds: %-18s %4d files\n' "$(basename "$target_dir")" \
    "$(find "$target_dir" -type f | wc -l)"
done

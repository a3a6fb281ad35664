#!/usr/bin/env bash
# Writes the seed corpus of every fuzz target into OUT/<target>/ from files already in the
# repository (tests/data, fuzz/seeds) and, when present, ../shared/data/meshes (bad, gltf,
# draco). A clone without ../shared gets the repository's seeds only (and says so).
# Seeds over 256 KiB are left out: they only slow the fuzzer down.
#   fuzz/make_corpus.sh OUT [SHARED_MESHES_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: $0 OUT [SHARED_MESHES_DIR]}"
shared="${2:-$root/../shared/data/meshes}"
data="$root/tests/data"
seeds="$root/fuzz/seeds"
max_bytes=262144
targets=(glb gltf gltf_external draco obj off ply stl image options upload)

rm -rf "$out"
for t in "${targets[@]}"; do mkdir -p "$out/$t"; done

# add TARGET FILE...: copies each small enough file as a seed named after its path.
add() {
  local target="$1"
  shift
  local f
  for f in "$@"; do
    [ -f "$f" ] || continue
    [ "$(stat -c %s "$f")" -le "$max_bytes" ] || continue
    cp "$f" "$out/$target/$(basename "$(dirname "$f")")__$(basename "$f")"
  done
}

# gltf_external_seed DIR: the .gltf of DIR followed by its .bin files, in fuzz_gltf_external's
# input layout ("\n--papernet-file:<name>\n" before each file).
gltf_external_seed() {
  local dir="$1" gltf bin
  for gltf in "$dir"/*.gltf; do
    [ -f "$gltf" ] || continue
    {
      cat "$gltf"
      for bin in "$dir"/*.bin; do
        [ -f "$bin" ] || continue
        printf '\n--papernet-file:%s\n' "$(basename "$bin")"
        cat "$bin"
      done
    } >"$out/gltf_external/$(basename "$dir")__$(basename "$gltf")"
  done
}

# upload_seed NAME QUERY CONTENT_TYPE BODY_FILE: fuzz_upload's input layout.
upload_seed() {
  { printf '%s\n%s\n' "$2" "$3"; cat "$4"; } >"$out/upload/$1"
}

# multipart_seed NAME [FIELD FILENAME CONTENT_TYPE FILE]...: a multipart/form-data upload.
multipart_seed() {
  local name="$1" boundary="papernetfuzzboundary"
  shift
  {
    printf '\nmultipart/form-data; boundary=%s\n' "$boundary"
    while [ $# -ge 4 ]; do
      printf -- '--%s\r\nContent-Disposition: form-data; name="%s"' "$boundary" "$1"
      [ -n "$2" ] && printf '; filename="%s"' "$2"
      printf '\r\n'
      [ -n "$3" ] && printf 'Content-Type: %s\r\n' "$3"
      printf '\r\n'
      cat "$4"
      printf '\r\n'
      shift 4
    done
    printf -- '--%s--\r\n' "$boundary"
  } >"$out/upload/$name"
}

add glb "$data"/*.glb
add gltf "$data"/gltf_external/*.gltf
gltf_external_seed "$data/gltf_external"
add draco "$seeds"/*.drc
add obj "$data"/*.obj "$seeds"/*.obj
add off "$seeds"/*.off
add ply "$data"/*.ply "$seeds"/*.ply
add stl "$data"/*.stl "$seeds"/*.stl
add options "$seeds"/options*
add image "$data"/CesiumMilkTruck/*.png "$data"/*.jpg
upload_seed raw_obj "strategy=TU&seed=2" model/obj "$seeds/cube_quads.obj"
upload_seed sniffed_ply "" application/octet-stream "$data/mirror.ply"
upload_seed draco_glb "format=glb" "" "$data/Box_Draco.glb"
multipart_seed multipart_off mesh tetra.off model/x-off "$seeds/tetra.off" \
  options "" application/json "$seeds/options.json"
multipart_seed multipart_gltf mesh Box.gltf model/gltf+json "$data/gltf_external/Box.gltf" \
  buffers Box0.bin application/octet-stream "$data/gltf_external/Box0.bin"

if [ -d "$shared" ]; then
  add glb "$shared"/bad/*.glb "$shared"/gltf/*.glb "$shared"/draco/*.glb
  add gltf "$shared"/bad/*.gltf "$shared"/bad/*/*.gltf "$shared"/gltf/*.gltf \
    "$shared"/gltf/*/*.gltf "$shared"/draco/*/*.gltf
  for dir in "$shared"/bad/*/ "$shared"/gltf/*/ "$shared"/draco/*/; do
    gltf_external_seed "${dir%/}"
  done
  add draco "$shared"/draco/*.drc
  add image "$shared"/gltf/*/*.png "$shared"/gltf/*/*.jpg "$shared"/draco/*/*.png \
    "$shared"/draco/*/*.jpg
  add obj "$shared"/bad/*.obj
  add off "$shared"/bad/*.off
  add ply "$shared"/bad/*.ply
  add stl "$shared"/bad/*.stl "$shared"/bad/*.STL
  echo "fuzz seeds: tests/data, fuzz/seeds and $shared"
else
  echo "fuzz seeds: tests/data and fuzz/seeds only ($shared not found)"
fi
for t in "${targets[@]}"; do printf '  %-14s %4d seeds\n' "$t" "$(ls "$out/$t" | wc -l)"; done

#!/usr/bin/env bash
# Writes a self-contained folder for running the STAR-NT benchmark on a bare Linux x86-64 machine
# that has a GPU driver (EGL) but none of our packages and no network to install them (a lent GPU
# box with no registry): the Release binary, the shared libraries it needs that such a machine may
# lack, the chosen suite scenes and a launcher.
#
# Usage: scripts/bundle.sh [--force] DIR [SCENES...]
#   SCENES    suite names, separate or comma-separated (default: the six headline scenes
#             magic_stars,chess,tree,hair,hairball,engine); see ../shared/scenes/README.md.
#   --force   replace an existing non-empty DIR.
# Environment:
#   STARNT_BINARY=FILE        bundle FILE instead of running scripts/build.sh and taking build/starnt
#   STARNT_SCENES_DIR=DIR     the suite folder (default: ../shared/scenes beside the checkout)
#   STARNT_BUNDLE_MAX_MIB=N   fail when the bundle exceeds N MiB (default 60)
#
# Layout: DIR/starnt (launcher: sets LD_LIBRARY_PATH to DIR/lib, checks for an EGL loader, then
# execs DIR/bin/starnt), DIR/bin/starnt (stripped), DIR/lib/ (bundled libraries; libstdc++ and
# libgcc_s in DIR/lib/gcc/, used only when the machine's own are older), DIR/scenes/ (a suite
# folder for `bench --suite-dir`), DIR/BUNDLE.txt (what is inside; `DIR/starnt --bundle-info`).
# On the target:  DIR/starnt bench --suite-dir DIR/scenes --scenes chess,tree --out results
# Never bundled, they must come from the target machine: glibc (libc, libm, libdl, libpthread,
# librt, libresolv, ld-linux) and the GL/EGL driver and dispatch libraries (libEGL*, libGL*,
# libOpenGL*, libgbm, libdrm, libnvidia*). libepoxy is bundled; it dlopen()s libEGL.so.1 at run time.
# The bundle is written into a temporary folder beside DIR and renamed at the end.
set -euo pipefail

die() { echo "bundle: $*" >&2; exit 1; }

force=0
if [[ ${1:-} == --force ]]; then force=1; shift; fi
[[ $# -ge 1 && -n $1 && $1 != -* ]] || die "usage: scripts/bundle.sh [--force] DIR [SCENES...]"
dest="${1%/}"; shift
[[ -n $dest ]] || dest=/

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
suite="${STARNT_SCENES_DIR:-$root/../shared/scenes}"
max_mib="${STARNT_BUNDLE_MAX_MIB:-60}"
[[ $max_mib =~ ^[0-9]+([.][0-9]+)?$ ]] || die "STARNT_BUNDLE_MAX_MIB must be a number of MiB, not '$max_mib'"

# --- the scene list --------------------------------------------------------------------------
scenes=()
for arg in "${@:-magic_stars,chess,tree,hair,hairball,engine}"; do
  IFS=, read -ra parts <<<"$arg"
  for s in "${parts[@]}"; do [[ -n $s ]] && scenes+=("$s"); done
done
[[ ${#scenes[@]} -gt 0 ]] || die "no scenes given"
[[ -d $suite ]] || die "scene suite folder $suite not found (set STARNT_SCENES_DIR)"
suite="$(cd "$suite" && pwd)"

# Suite name -> file, from the suite README's table ("| name | folder/file | ..."): the same table
# `starnt bench` resolves --scenes with (src/bench/bench_plan.cpp, suiteScenes()).
declare -A scene_file=()
if [[ -f $suite/README.md ]]; then
  while IFS='|' read -r _ name file _; do
    name="${name//[[:space:]]/}"; file="${file//[[:space:]]/}"
    [[ $name =~ ^[a-z0-9_]+$ && $file == */* ]] && scene_file[$name]="$file"
  done < <(grep '^|' "$suite/README.md")
fi
declare -A seen=()
for s in "${scenes[@]}"; do
  [[ -z ${seen[$s]:-} ]] || die "scene '$s' is listed twice"
  seen[$s]=1
  if [[ -z ${scene_file[$s]:-} ]]; then
    known="$(printf '%s\n' "${!scene_file[@]}" | sort | paste -sd, -)"
    die "unknown scene '$s' (suite scenes in $suite: ${known:-none found: no README.md table})"
  fi
  [[ -f $suite/${scene_file[$s]} ]] || die "scene '$s': $suite/${scene_file[$s]} is missing"
done

# --- where to write ----------------------------------------------------------------------------
if [[ -e $dest || -L $dest ]]; then
  [[ -d $dest && ! -L $dest ]] || die "$dest exists and is not a folder"
  if [[ -n $(ls -A "$dest") && $force -ne 1 ]]; then
    die "$dest exists and is not empty (pass --force as the first argument to replace it)"
  fi
fi
parent="$(dirname "$dest")"
mkdir -p "$parent"
tmp="$(mktemp -d "$parent/.$(basename "$dest").bundle.XXXXXX")"
old=""
cleanup() { rm -rf "$tmp"; [[ -z $old ]] || rm -rf "$old"; }
trap cleanup EXIT
trap 'exit 130' INT TERM

# --- the binary --------------------------------------------------------------------------------
if [[ -n ${STARNT_BINARY:-} ]]; then
  bin="$STARNT_BINARY"
  [[ -f $bin && -x $bin ]] || die "STARNT_BINARY=$bin is not an executable file"
  origin="STARNT_BINARY=$bin"
else
  echo "bundle: building (scripts/build.sh)" >&2
  bash "$root/scripts/build.sh" >&2
  bin="$root/build/starnt"
  [[ -x $bin ]] || die "the build did not produce $bin"
  origin="scripts/build.sh, $(git -C "$root" describe --always --dirty --abbrev=12 2>/dev/null || echo 'commit unknown')"
fi
if command -v file >/dev/null; then
  file -L "$bin" | grep -q 'ELF 64-bit.*x86-64' || die "$bin is not an x86-64 ELF binary"
fi
mkdir -p "$tmp/bin" "$tmp/lib/gcc" "$tmp/scenes"
cp -L "$bin" "$tmp/bin/starnt"
chmod 755 "$tmp/bin/starnt"
if command -v strip >/dev/null; then
  strip "$tmp/bin/starnt"; stripped=stripped
else
  echo "bundle: warning: no strip: the binary is copied unstripped" >&2; stripped="not stripped"
fi

# --- libraries ---------------------------------------------------------------------------------
# From the target machine, never bundled: glibc and the GL/EGL driver and dispatch libraries.
system_re='^(ld-linux.*|linux-vdso.*|lib(c|m|dl|pthread|rt|resolv|util|anl|nsl|mvec|BrokenLocale|thread_db|nss_[a-z]+)\.so(\..*)?|lib(EGL|GL|OpenGL|gbm|drm|nvidia|cuda).*)$'
gcc_re='^lib(stdc\+\+|gcc_s)\.so'

# Prints "NAME PATH" for each resolved dependency of $1; fails on an unresolved one.
deps() {
  local out
  out="$(LD_LIBRARY_PATH="${2:-}" ldd "$1" 2>&1)" || die "ldd $1 failed: $out"
  if grep -q 'not found' <<<"$out"; then
    die "$1 has unresolved libraries on this machine: $(grep 'not found' <<<"$out" | awk '{print $1}' | paste -sd' ' -)"
  fi
  awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' <<<"$out"
}
declare -A bundled=()
queue=("$tmp/bin/starnt")
while [[ ${#queue[@]} -gt 0 ]]; do
  obj="${queue[0]}"; queue=("${queue[@]:1}")
  found="$(deps "$obj")"
  while read -r name path; do
    [[ -n $name && -z ${bundled[$name]:-} ]] || continue
    [[ $name =~ $system_re ]] && continue
    sub=""; [[ $name =~ $gcc_re ]] && sub=gcc/
    cp -L "$path" "$tmp/lib/$sub$name"
    chmod 644 "$tmp/lib/$sub$name"
    bundled[$name]="$sub$name"
    queue+=("$tmp/lib/$sub$name")  # its own dependencies (ldd on the binary lists them already)
  done <<<"$found"
done
[[ -n ${bundled[libepoxy.so.0]:-} ]] || die "libepoxy.so.0 was not bundled (ldd does not list it for $bin)"
# Check: with the bundle's folders first, every library that is not the machine's own resolves
# inside the bundle.
found="$(deps "$tmp/bin/starnt" "$tmp/lib:$tmp/lib/gcc")"
while read -r name path; do
  [[ $name =~ $system_re || $path == "$tmp/lib/"* ]] || die "$name resolves to $path, outside the bundle"
done <<<"$found"
# Levels the launcher compares with the machine's: the newest glibc symbol version the binary and
# the libraries need, and the bundled libstdc++'s newest GLIBCXX version.
# (The gcc runtime counts only where the launcher uses it.)
glibc_level() { find "$@" -maxdepth 1 -type f -exec cat {} + | { grep -ao 'GLIBC_2\.[0-9]*' || true; } | sed 's/GLIBC_//' | sort -uV | tail -n1; }
glibc_needed="$(glibc_level "$tmp/bin" "$tmp/lib")"
echo "${glibc_needed:=2.0}" > "$tmp/lib/GLIBC_NEEDED"
if [[ -f $tmp/lib/gcc/libstdc++.so.6 ]]; then
  glibc_gcc="$(glibc_level "$tmp/lib/gcc")"
  printf '%s\n' "$glibc_needed" "${glibc_gcc:-2.0}" | sort -V | tail -n1 > "$tmp/lib/gcc/GLIBC_NEEDED"
  grep -ao 'GLIBCXX_3\.4\.[0-9]*' "$tmp/lib/gcc/libstdc++.so.6" | sed 's/GLIBCXX_3\.4\.//' | sort -n | tail -n1 > "$tmp/lib/gcc/GLIBCXX_LEVEL"
fi

# --- scenes ------------------------------------------------------------------------------------
# Each scene's file plus the non-mesh files of its folder (READMEs, licences, .bin/.mtl/textures);
# other meshes sharing the folder (e.g. powerplant's two) are left out.
[[ -f $suite/README.md ]] && cp "$suite/README.md" "$tmp/scenes/README.md"
for s in "${scenes[@]}"; do
  rel="${scene_file[$s]}"; folder="$(dirname "$rel")"
  mkdir -p "$tmp/scenes/$folder"
  cp "$suite/$rel" "$tmp/scenes/$rel"
  for f in "$suite/$folder"/*; do
    [[ -f $f ]] || continue
    case "${f,,}" in *.glb|*.gltf|*.obj|*.ply|*.fbx|*.stl) continue ;; esac
    cp "$f" "$tmp/scenes/$folder/"
  done
done
chmod -R u+w "$tmp/scenes"

# --- launcher ----------------------------------------------------------------------------------
cat > "$tmp/starnt" <<'LAUNCHER'
#!/usr/bin/env bash
# STAR-NT bundle launcher (written by scripts/bundle.sh): runs bin/starnt with the bundled
# libraries. Same arguments as starnt; `bench` without --suite-dir uses this bundle's scenes.
#   starnt --bundle-info        what the bundle holds, and what this machine provides
#   STARNT_SKIP_EGL_CHECK=1     skip the check for the machine's EGL loader (libEGL.so.1)
#   STARNT_LIB_DIRS=D1:D2       where to look for the machine's libraries when ldconfig lacks them
set -euo pipefail
export PATH="${PATH:-/usr/local/bin:/usr/bin:/bin}:/usr/sbin:/sbin"
here="$(dirname "$(readlink -f -- "${BASH_SOURCE[0]}")")"
die() { echo "starnt bundle: $*" >&2; exit 1; }
cache="$(ldconfig -p 2>/dev/null || true)"
# The machine's x86-64 library $1 (ldconfig's cache, then LD_LIBRARY_PATH and common folders).
find_lib() {
  local line d dirs
  while read -r line; do
    if [[ $line == "$1 (libc6,x86-64"* ]]; then echo "${line##*=> }"; return 0; fi
  done <<<"$cache"
  IFS=: read -ra dirs <<<"${LD_LIBRARY_PATH:-}:${STARNT_LIB_DIRS:-/usr/lib/x86_64-linux-gnu:/lib/x86_64-linux-gnu:/usr/lib64:/lib64:/usr/lib:/lib:/usr/local/nvidia/lib64:/usr/local/lib}"
  for d in "${dirs[@]}"; do if [[ -n $d && -e $d/$1 ]]; then echo "$d/$1"; return 0; fi; done
  return 1
}
# The bundled libstdc++/libgcc_s only when the machine's libstdc++ is missing or older (an older
# one forced on the machine's own GL driver, or on the Python the bench runs, would break them).
libs="$here/lib" cxx="system" need="$(<"$here/lib/GLIBC_NEEDED")"
if [[ -f $here/lib/gcc/GLIBCXX_LEVEL ]]; then
  sys="$(find_lib libstdc++.so.6 || true)"
  lvl=-1; [[ -z $sys ]] || lvl="$({ grep -ao 'GLIBCXX_3\.4\.[0-9]*' "$sys" || true; } | sed 's/.*\.//' | sort -n | tail -n1)"
  if (( ${lvl:--1} < $(<"$here/lib/gcc/GLIBCXX_LEVEL") )); then
    libs="$libs:$here/lib/gcc" cxx="bundled" need="$(<"$here/lib/gcc/GLIBC_NEEDED")"
  fi
fi
egl="$(find_lib libEGL.so.1 || true)"
have="$(getconf GNU_LIBC_VERSION 2>/dev/null || true)"; have="${have#glibc }"
if [[ ${1:-} == --bundle-info ]]; then
  cat "$here/BUNDLE.txt"
  echo "size: $(du -sk "$here" | awk '{printf "%.1f MiB", $1 / 1024}')"
  echo "this machine: glibc ${have:-unknown} (needs $need), libEGL.so.1 ${egl:-MISSING}, libstdc++ $cxx"
  exit 0
fi
if [[ $have =~ ^([0-9]+)\.([0-9]+) ]] && (( BASH_REMATCH[1] * 1000 + BASH_REMATCH[2] < ${need%%.*} * 1000 + ${need#*.} )); then
  die "this machine has glibc $have; the bundle needs glibc >= $need (bundle on an older distribution)"
fi
if [[ ${STARNT_SKIP_EGL_CHECK:-0} != 1 && -z $egl ]]; then
  die "no libEGL.so.1 on this machine: install the NVIDIA driver's EGL libraries (libnvidia-egl / libegl1) or Mesa's libegl1 and libegl-mesa0 (STARNT_SKIP_EGL_CHECK=1 skips this check)"
fi
export LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
args=("$@")
if [[ ${1:-} == bench ]]; then
  suite=1
  for a in "$@"; do if [[ $a == --suite-dir || $a == --suite-dir=* ]]; then suite=0; fi; done
  if (( suite )); then args+=(--suite-dir "$here/scenes"); fi
fi
exec "$here/bin/starnt" "${args[@]}"
LAUNCHER
chmod 755 "$tmp/starnt"

# --- manifest and size -------------------------------------------------------------------------
mib() { awk -v b="$1" 'BEGIN {printf "%.1f", b / 1048576}'; }
{
  echo "STAR-NT benchmark bundle (scripts/bundle.sh), made $(date -u +%Y-%m-%dT%H:%MZ) on $(. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME:-}" || uname -sr)"
  echo "binary: bin/starnt, $(mib "$(stat -c %s "$tmp/bin/starnt")") MiB, $stripped; from $origin"
  echo "needs on the machine: Linux x86-64, glibc >= $glibc_needed ($(cat "$tmp/lib/gcc/GLIBC_NEEDED" 2>/dev/null || echo "$glibc_needed") with the bundled gcc runtime), an EGL driver (libEGL.so.1: NVIDIA's or Mesa's)"
  echo "libraries (lib/): $(cd "$tmp/lib" && ls lib* 2>/dev/null | paste -sd' ' - || true)"
  echo "gcc runtime (lib/gcc/, used when the machine's libstdc++ is older than GLIBCXX_3.4.$(cat "$tmp/lib/gcc/GLIBCXX_LEVEL" 2>/dev/null || echo '?')): $(cd "$tmp/lib/gcc" && ls lib* 2>/dev/null | paste -sd' ' - || true)"
  echo "scenes (scenes/): $(IFS=,; echo "${scenes[*]}")"
  echo "run: ./starnt bench --scenes $(IFS=,; echo "${scenes[*]}") --out results   (--suite-dir defaults to this bundle's scenes/)"
} > "$tmp/BUNDLE.txt"

bytes="$(du -sb "$tmp" | awk '{print $1}')"
size="$(mib "$bytes")"
if awk -v s="$bytes" -v m="$max_mib" 'BEGIN {exit !(s > m * 1048576)}'; then
  die "the bundle is $size MiB, over the ${max_mib} MiB limit (STARNT_BUNDLE_MAX_MIB); fewer scenes?"
fi

# --- publish -----------------------------------------------------------------------------------
if [[ -d $dest ]]; then
  if [[ -n $(ls -A "$dest") ]]; then
    old="$(mktemp -d "$parent/.$(basename "$dest").old.XXXXXX")"
    mv -T "$dest" "$old"
  else
    rmdir "$dest"
  fi
fi
chmod 755 "$tmp"
mv -T "$tmp" "$dest"
echo "bundle: $dest: ${#bundled[@]} libraries, ${#scenes[@]} scenes ($(IFS=,; echo "${scenes[*]}")), $size MiB"

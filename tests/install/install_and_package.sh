#!/usr/bin/env bash
# Installs depthprec into a temporary prefix and builds its Debian package, then runs both
# installed binaries from an unrelated directory: they must give the build's own bytes, and the
# package must depend on Debian's packages for everything it loads. Run by ctest as
# `install_and_package`; argument: the build directory.
set -euo pipefail
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(mts -t standard -f unorm24 --distances 2,1024 --frames 4 --format-out csv --no-timing -q)
"$build/depthprec" "${args[@]}" > "$tmp/expected.csv"

cmake --install "$build" --prefix "$tmp/prefix" > /dev/null
cd "$tmp"
# The kernels the build compiled ship with it (when the build had an OpenCL device), and the
# installed binary runs from them with PoCL's cache empty: the same bytes.
if ls "$build"/kernel-cache/*.bin > /dev/null 2>&1; then
  [ "$(ls "$tmp"/prefix/share/depthprec/kernels/*.bin | wc -l)" -eq \
    "$(ls "$build"/kernel-cache/*.bin | wc -l)" ] || { echo "compiled kernels not installed" >&2; exit 1; }
fi
mkdir "$tmp/pocl"
POCL_CACHE_DIR="$tmp/pocl" "$tmp/prefix/bin/depthprec" "${args[@]}" > installed.csv
cmp expected.csv installed.csv
# The scenes ship beside it, and run from there.
"$tmp/prefix/bin/depthprec" mts "$tmp/prefix/share/depthprec/scenes/validation.json" \
  -t linear -f unorm16 --distances 8 --frames 2 -q > /dev/null
test -f "$tmp/prefix/share/doc/depthprec/docs/spec.md"

(cd "$build" && cpack -G DEB -B "$tmp/package" > /dev/null)
deb=$(ls "$tmp"/package/depthprec_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libfmt libepoxy0 libstdc++6 "pocl-opencl-icd | opencl-icd"; do
  case "$depends" in
    *"$lib"*) ;;
    *) echo "package Depends lacks $lib: $depends" >&2; exit 1 ;;
  esac
done
dpkg-deb -x "$deb" "$tmp/root"
"$tmp/root/usr/bin/depthprec" "${args[@]}" > packaged.csv
cmp expected.csv packaged.csv
echo "installed and packaged: $(basename "$deb"), Depends: $depends"

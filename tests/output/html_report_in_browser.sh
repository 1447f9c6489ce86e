#!/usr/bin/env bash
# `depthprec report` in a real browser: the page is self-contained (nothing fetched from anywhere),
# headless Chromium loads it without a console message, and its screenshot is not blank.
# The same page built from a table's JSON (--from) shows the same MTS.
# usage: html_report_in_browser.sh DEPTHPREC
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=(-t standard,reversed,linear -f unorm24,float32 --kernel 24x24 --frames 4 --far 1e5
       --distances 2,64,2048,65536,1e6)
# A scene that asks for shadows (docs/shadow.md) gets the shadow section.
shadow=(--set 'shadow={"splits":[10,40],"planes":64,"engines":["bevy","godot"]}')

"$exe" report "${scene[@]}" "${shadow[@]}" --no-timing -q -o "$tmp/report.html"
page="$tmp/report.html"
fail() { echo "FAIL: $*" >&2; exit 1; }

grep -q '<svg' "$page" || fail "no inline SVG plot"
grep -q 'Attribution' "$page" || fail "no attribution section"
grep -q 'Lapidous-Jiao' "$page" || fail "no Lapidous-Jiao figures (standard is LJ's z buffer)"
grep -q 'Shadow-map bias' "$page" || fail "no shadow section though the scene has a shadow block"
grep -q '<td class="left">binary32 (this page&#39;s bound)</td>' "$page" ||
  fail "the implementations section does not mark the page's bound model"
grep -q '<td class="left">vulkan_min</td>' "$page" || fail "the implementations section lists no envelope"
grep -q '<td class="left">10-40</td>' "$page" || fail "the shadow section has no row for cascade 2"
grep -q '<td class="left">godot</td>' "$page" || fail "the shadow section has no engine rows"
# Nothing from outside the page: no linked stylesheet, script, image or font; the SVG's own
# references (href='#gpPt1', url(#gpPat1)) point inside the page.
outside='<link|<script|<img|<iframe|<object|<embed|@import|url\((?!#)|(src|href)\s*=\s*["'"'"'](?!#)'
if grep -Piq "$outside" "$page"; then
  fail "the page refers to something outside itself: $(grep -Pio "$outside" "$page" | head -3)"
fi

browser=$(command -v chromium || command -v chromium-browser || true)
[ -n "$browser" ] || fail "chromium is not installed (scripts/setup.sh installs it)"
log="$tmp/chromium.log"
HOME="$tmp" timeout 120 "$browser" --headless --no-sandbox --disable-gpu --no-first-run \
  --enable-logging=stderr --v=0 --window-size=1280,2400 \
  --screenshot="$tmp/shot.png" "file://$page" > "$log" 2>&1 || { cat "$log" >&2; fail "chromium failed"; }
# Chromium logs every console message (errors, failed loads, script errors) as CONSOLE.
if grep -q 'CONSOLE' "$log"; then grep 'CONSOLE' "$log" >&2; fail "console messages"; fi
[ -s "$tmp/shot.png" ] || fail "no screenshot"

# The screenshot decoded (PNG, stdlib only): not one colour, and the dark pixels of text and
# plot lines cover a visible share of it.
python3 - "$tmp/shot.png" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w, h, bpp = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, colour = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and colour in (2, 6), f"unexpected PNG type {depth}/{colour}"
        bpp = 3 if colour == 2 else 4
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
stride, prev, rows = w * bpp, bytearray(w * bpp), []
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
colours, dark = set(), 0
for line in rows[::4]:
    for x in range(0, stride, bpp * 4):
        px = tuple(line[x:x + 3])
        colours.add(px)
        dark += sum(px) < 200
sampled = (h // 4 + 1) * (w // 4 + 1)
print(f"screenshot {w}x{h}: {len(colours)} colours, {100 * dark / sampled:.2f} % dark pixels")
assert len(colours) > 20, "the screenshot is (nearly) one colour"
assert dark / sampled > 0.005, "almost nothing dark on the page: no text rendered"
PY

# --from: the same scene's table JSON gives a page with the same MTS cells.
"$exe" table "${scene[@]}" --no-timing -q --format-out json -o "$tmp/table.json"
"$exe" report --from "$tmp/table.json" -q -o "$tmp/from.html"
# The MTS table's cells, without the dominant-factor letter (the table ran without --attribute).
cells() {
  sed -n '/<h2>Minimum triangle separation/,/<\/table>/p' "$1" |
    grep -o '<td class="[^"]*"[^>]*>[^<]*</td>' | sed 's/<[^>]*>//g; s/ [SAV]$//'
}
[ "$(cells "$page" | wc -l)" -eq 40 ] || fail "the MTS table has $(cells "$page" | wc -l) cells, not 5 x (2 + 6)"
diff <(cells "$page") <(cells "$tmp/from.html") >&2 ||
  fail "report --from table.json shows other numbers than the report that ran the scene"
# The guaranteed MTS: a grid of the rows' mts_bound, each the JSON's to the page's four digits
# ("-" where a row has none), the same whether the page ran the scene or read its table.
bound_cells() {
  sed -n '/<h2>Guaranteed MTS/,/<\/table>/p' "$1" |
    grep -o '<td class="[^"]*"[^>]*>[^<]*</td>' | sed 's/<[^>]*>//g'
}
diff <(bound_cells "$page") <(bound_cells "$tmp/from.html") >&2 ||
  fail "report --from table.json shows other guaranteed MTS than the report that ran the scene"
python3 - "$tmp/table.json" > "$tmp/bounds.txt" <<'PY'
import json, math, sys
rows = json.load(open(sys.argv[1]))["rows"]
labels = list(dict.fromkeys(f"{r['technique']}/{r['format']}/{r['depth_range']}" for r in rows))
at = {(r["z"], f"{r['technique']}/{r['format']}/{r['depth_range']}"): r for r in rows}
def human(v):
    return "inf" if v == "inf" else "0" if v == 0 else f"{v:.4g}"
for z in sorted({r["z"] for r in rows}):
    print(human(z))
    for label in labels:
        print(human(at[(z, label)]["mts_bound"]) if "mts_bound" in at[(z, label)] else "-")
PY
diff <(bound_cells "$tmp/from.html") "$tmp/bounds.txt" >&2 ||
  fail "the guaranteed MTS grid differs from the rows' mts_bound"
grep -q '[0-9]e-0[0-9]' "$tmp/bounds.txt" || fail "no finite guaranteed MTS to check"
echo "report: self-contained, loaded by $browser without a console message, screenshot checked"

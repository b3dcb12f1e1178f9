#!/usr/bin/env bash
# Renders a report page with headless Chromium at phone (390 px) and desktop
# (1440 px) width: a screenshot of the top of the page at each width
# (SHOT_HEIGHT px, 2400 by default: the summary, measured against predicted
# and what follows them, not the whole page, which runs to tens of thousands
# of pixels), and one line per width of what is checked mechanically over the
# whole page:
#
#   width=390 inner=390 scroll=390 overflow=0 images=24 broken=0 first_table=channel
#
# overflow=1 means the page is wider than the window (it scrolls sideways);
# broken counts images that did not load; first_table is the first header
# cell of the first table on the page.
#
# Usage: [SHOT_HEIGHT=PX] scripts/screenshot-report.sh REPORT_DIR/index.html [OUT_DIR]
# Needs Chromium (Debian: apt-get install chromium). Exit status 2 when absent.
set -euo pipefail

page=${1:?usage: $0 REPORT_DIR/index.html [OUT_DIR]}
out=${2:-$(dirname "$page")/screenshots}
browser=${CHROMIUM:-}
if [[ -z $browser ]]; then
    for b in chromium chromium-browser google-chrome; do
        if command -v "$b" >/dev/null 2>&1; then browser=$b; break; fi
    done
fi
if [[ -z $browser ]] || ! command -v "$browser" >/dev/null 2>&1; then
    echo "chromium not found: install it (Debian: apt-get install chromium) or set CHROMIUM" >&2
    exit 2
fi
height=${SHOT_HEIGHT:-2400}
mkdir -p "$out"
dir=$(cd "$(dirname "$page")" && pwd)
name=$(basename "$page")
# Headless Chromium will not make a window narrower than 500 px, so the page
# is loaded in an iframe of the width under test (its media queries see that
# width), from a probe page beside it that measures the layout once every
# image has loaded.
probe="$dir/.probe-$$.html"
probe_js="$dir/.probe-$$.js"
trap 'rm -f "$probe" "$probe_js"' EXIT
cat > "$probe_js" <<'JS'
const f = document.getElementById("f");
f.addEventListener("load", async () => {
  const doc = f.contentDocument;
  const imgs = [...doc.images];
  imgs.forEach(i => { i.loading = "eager"; });
  await Promise.all(imgs.map(i => i.complete ? null :
    new Promise(r => { i.onload = r; i.onerror = r; })));
  const broken = imgs.filter(i => !(i.complete && i.naturalWidth > 0)).length;
  const d = doc.documentElement;
  const inner = f.contentWindow.innerWidth;
  const th = doc.querySelector("table th");
  document.body.setAttribute("data-check",
    `inner=${inner} scroll=${d.scrollWidth} overflow=${d.scrollWidth > inner ? 1 : 0} ` +
    `images=${imgs.length} broken=${broken} first_table=${th ? th.textContent.trim().split(" ")[0] : "none"}`);
});
JS

flags=(--headless=new --no-sandbox --disable-gpu --hide-scrollbars --disable-dev-shm-usage
       --allow-file-access-from-files --run-all-compositor-stages-before-draw
       --virtual-time-budget=20000)
for width in 390 1440; do
    cat > "$probe" <<HTML
<!DOCTYPE html><html><head><meta charset="utf-8"><style>body{margin:0}iframe{border:0;display:block}</style></head>
<body><iframe id="f" src="$name" style="width:${width}px;height:${height}px"></iframe>
<script src="$(basename "$probe_js")"></script></body></html>
HTML
    dom=$("$browser" "${flags[@]}" --window-size="$(( width < 500 ? 500 : width )),$height" --dump-dom "file://$probe" 2>/dev/null || true)
    result=$(grep -o 'data-check="[^"]*"' <<<"$dom" | sed -e 's/^data-check="//' -e 's/"$//' || true)
    echo "width=$width ${result:-check=missing}"
    # The top $height px of the page at this width.
    "$browser" "${flags[@]}" --window-size="$width,$height" \
        --screenshot="$out/report-$width.png" "file://$probe" >/dev/null 2>&1 || true
done
echo "screenshots: $out/report-390.png $out/report-1440.png"

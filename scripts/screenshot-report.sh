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
# Before the browser, every link of the page is followed on disk: each
# href, src and srcset that is not a web address must be a path relative to
# the page that names an existing file, and each #anchor an id on the page
# it points into. A broken link is named on stderr and the script exits 1
# (with or without Chromium); so it does when an image did not load.
#
# Usage: [SHOT_HEIGHT=PX] scripts/screenshot-report.sh REPORT_DIR/index.html [OUT_DIR]
# Needs Chromium (Debian: apt-get install chromium). Exit status 2 when absent
# (after the link check), 1 on a broken link or image.
set -euo pipefail

page=${1:?usage: $0 REPORT_DIR/index.html [OUT_DIR]}
[[ -f $page ]] || { echo "$page: no such file" >&2; exit 1; }

# The ids of an HTML file, one a line.
ids_of() { grep -o ' id="[^"]*"' "$1" | sed -e 's/^ id="//' -e 's/"$//' || true; }
# Every href, src and srcset URL of an HTML file, entities decoded, one a line.
links_of() {
    grep -oE ' (href|src|srcset)="[^"]*"' "$1" \
        | sed -E -e 's/^ [a-z]+="//' -e 's/"$//' -e 's/, /\n/g' \
        | sed -E -e 's/ [0-9.]+[wx]$//' -e 's/&quot;/"/g' -e "s/&#39;/'/g" \
                 -e 's/&lt;/</g' -e 's/&gt;/>/g' -e 's/&amp;/\&/g' || true
}
page_dir=$(dirname "$page")
page_ids=$(ids_of "$page")
links=0
bad_links=0
while IFS= read -r link; do
    [[ -z $link ]] && continue
    links=$((links + 1))
    why=
    case $link in
        http://*|https://*) continue ;;
        file:*|/*) why="is absolute: it breaks when the report is moved" ;;
        \#*) grep -qxF -- "${link#\#}" <<<"$page_ids" || why="names no id on the page" ;;
        *)
            path=${link%%#*}
            # %XX escapes as the file system spells the name.
            file="$page_dir/$(printf '%b' "${path//%/\\x}")"
            if [[ ! -e $file ]]; then
                why="resolves to $file, which does not exist"
            elif [[ $link == *#* ]] && ! ids_of "$file" | grep -qxF -- "${link#*#}"; then
                why="names no id on $file"
            fi
            ;;
    esac
    if [[ -n $why ]]; then
        echo "broken link in $page: \"$link\" $why" >&2
        bad_links=$((bad_links + 1))
    fi
done < <(links_of "$page")
echo "links=$links broken_links=$bad_links"
if (( bad_links > 0 )); then
    exit 1
fi
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

# A profile of its own for each run: two renderings at once (two test runs
# on one machine) otherwise share Chromium's default profile, and one of
# them was seen to wait on it without end.
profile=$(mktemp -d)
trap 'rm -rf "$probe" "$probe_js" "$profile"' EXIT
flags=(--headless=new --no-sandbox --disable-gpu --hide-scrollbars --disable-dev-shm-usage
       --allow-file-access-from-files --run-all-compositor-stages-before-draw
       --virtual-time-budget=20000 --user-data-dir="$profile")
# Chromium under a time limit (BROWSER_LIMIT_S, 120 s by default; a
# rendering takes a few seconds), tried twice: a stalled browser is a
# failed check, not a hung test run.
browser_run() {
    local limit=${BROWSER_LIMIT_S:-120} try
    for try in 1 2; do
        if timeout --kill-after=10 "$limit" "$browser" "${flags[@]}" "$@" 2>/dev/null; then
            return 0
        fi
        echo "chromium did not finish within ${limit} s (try $try of 2)" >&2
    done
    return 1
}
broken_images=0
for width in 390 1440; do
    cat > "$probe" <<HTML
<!DOCTYPE html><html><head><meta charset="utf-8"><style>body{margin:0}iframe{border:0;display:block}</style></head>
<body><iframe id="f" src="$name" style="width:${width}px;height:${height}px"></iframe>
<script src="$(basename "$probe_js")"></script></body></html>
HTML
    dom=$(browser_run --window-size="$(( width < 500 ? 500 : width )),$height" --dump-dom "file://$probe" || true)
    result=$(grep -o 'data-check="[^"]*"' <<<"$dom" | sed -e 's/^data-check="//' -e 's/"$//' || true)
    echo "width=$width ${result:-check=missing}"
    if [[ $result =~ broken=([0-9]+) ]] && (( BASH_REMATCH[1] > 0 )); then
        broken_images=1
    fi
    # The top $height px of the page at this width.
    browser_run --window-size="$width,$height" \
        --screenshot="$out/report-$width.png" "file://$probe" >/dev/null || true
done
echo "screenshots: $out/report-390.png $out/report-1440.png"
if (( broken_images )); then
    echo "an image of $page did not load (broken>0 above)" >&2
    exit 1
fi

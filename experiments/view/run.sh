#!/usr/bin/env bash
# Pages of `coons view` and their screenshots in headless Chromium (software WebGL, SwiftShader):
# the dome at α = −1/4 (the Coons net) and at α = 0.2, the sphere cap with ribbons on its C1-weight
# slider, and a triangular boundary. Pages go to build/view-pages (not committed), the PNGs and
# figures.md (the pages' sizes and the energies the README quotes, computed) here.
# Usage: experiments/view/run.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build}
pages=$build/view-pages
mkdir -p "$pages"
coons=$build/coons
"$coons" view "$root/data/boundaries/dome.json" --out "$pages/dome.html" --force > "$pages/dome.json"
"$coons" view "$root/data/boundaries/sphere_cap_ribbons.json" --out "$pages/cap.html" --force > "$pages/cap.json"
"$coons" view "$root/data/triangles/dome_half.json" --out "$pages/dome_half.html" --force > "$pages/dome_half.json"
python3 "$here/figures.py" "$coons" "$pages" "$here/figures.md"
shot() {  # PAGE#FRAGMENT OUT.png
  chromium --headless=new --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader \
    --window-size=1200,660 --virtual-time-budget=5000 --screenshot="$2" "file://$1" > /dev/null 2>&1
}
shot "$pages/dome.html#alpha=-0.25" "$here/dome_alpha_-0.25.png"
shot "$pages/dome.html#alpha=0.2" "$here/dome_alpha_0.2.png"
shot "$pages/cap.html#weight=0.5" "$here/sphere_cap_weight_0.5.png"
shot "$pages/dome_half.html#alpha=-0.1667" "$here/dome_half_c_-0.1667.png"
shot "$pages/dome_half.html#alpha=0.0032" "$here/dome_half_c_0.0032.png"
ls -la "$here"/*.png

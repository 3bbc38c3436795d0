#!/usr/bin/env bash
# Checks that the Python wheel stands on its own, as a Dask worker or any user without this
# repository's build trees needs: builds it (pip wheel: CMake compiles the core and the cffi
# extension into it), installs it into a fresh virtual environment outside the repository,
# moves every build tree of the repository aside, then imports progsim there and runs a
# preview. The build trees come back whatever happens.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
python=${PYTHON:-python3}
source scripts/ccache_env.sh
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1

work=$(mktemp -d)
aside=()
restore() {
  for dir in "${aside[@]}"; do mv "$root/$dir.aside" "$root/$dir"; done
  rm -rf "$work"
}
trap restore EXIT

echo "== building the wheel =="
if ! "$python" -m pip wheel --quiet --no-deps -w "$work/wheels" ./bindings/python; then
  echo "isolated build failed; retrying with --no-build-isolation" >&2
  "$python" -m pip wheel --quiet --no-deps --no-build-isolation -w "$work/wheels" ./bindings/python
fi
wheel=$(ls "$work"/wheels/progsim-*.whl)
echo "test_wheel: built $(basename "$wheel") ($(du -k "$wheel" | cut -f1) KiB)"

echo "== installing it into a fresh virtual environment in $work/venv =="
"$python" -m venv "$work/venv"
"$work/venv/bin/python" -m pip install --quiet "$wheel"

for dir in build bindings/python/build bindings/python/src/progsim.egg-info; do
  if [ -e "$dir" ]; then
    mv "$dir" "$dir.aside"
    aside+=("$dir")
  fi
done
echo "test_wheel: moved aside ${aside[*]:-nothing}"

cd "$work"
"$work/venv/bin/python" - "$root" <<'PY'
import subprocess, sys
from pathlib import Path
import numpy as np
import progsim

root = Path(sys.argv[1])
package = Path(progsim.__file__).resolve().parent
assert root not in package.parents, f"progsim imported from the repository: {package}"
extension = next(package.glob("_progsim_cffi*.so"))
linked = subprocess.run(["ldd", str(extension)], capture_output=True, text=True, check=True).stdout
progsim_line = next(line for line in linked.splitlines() if "libprogsim" in line)
assert str(package) in progsim_line, f"the extension links {progsim_line.strip()}"
assert str(root) not in linked, f"the extension still depends on {root}:\n{linked}"

vertices = np.array([[x, y, 0.0] for y in range(5) for x in range(5)], dtype=float) * 0.25
faces = [(j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1) for j in range(4) for i in range(4)]
faces += [(j * 5 + i, (j + 1) * 5 + i + 1, (j + 1) * 5 + i) for j in range(4) for i in range(4)]
with progsim.Hierarchy(vertices, np.array(faces, dtype=np.int32)) as hierarchy:
    with progsim.Simulation(hierarchy, pinned=[20, 24], gravity=(0, 0, -9.81)) as sim:
        sim.step_preview(5)
        x = sim.positions()
assert np.isfinite(x).all() and x[:, 2].min() < -1e-3, x[:, 2].min()
print(f"test_wheel: progsim {progsim.library_version()} from {package}: 5 preview steps, "
      f"lowest vertex at z = {x[:, 2].min():.4f} m; libprogsim from {progsim_line.split()[2]}")
PY

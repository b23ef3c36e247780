# Sourced by the rendering benchmark scripts. find_numpy_python NAME: sets `py` to a python3
# that imports numpy and matplotlib ($PYTHON first, then python3, then Debian's own: a pyenv
# python3 ahead in PATH lacks Debian's python3-numpy and python3-matplotlib).
find_numpy_python() {
  py=""
  for candidate in ${PYTHON:-} python3 /usr/bin/python3; do
    if "$candidate" -c 'import numpy, matplotlib' 2>/dev/null; then py="$candidate"; return 0; fi
  done
  echo "$1: no python3 with numpy and matplotlib (Debian: python3-numpy python3-matplotlib)" >&2
  exit 1
}

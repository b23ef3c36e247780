# README.md's results table and docs/results.md are what bench/results_doc.py makes of the
# committed result files (bench/results, bench/render, bench/scale): neither drifts from the data.
set -euo pipefail
"${PYTHON:-python3}" "${SOURCE_DIR:?}/bench/results_doc.py" --check

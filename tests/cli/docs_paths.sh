#!/usr/bin/env bash
# The documentation cites no path outside the repository: no ../shared, /work or /tmp in the README,
# CONTRIBUTING.md and the Markdown files under docs/ and examples/. Usage: docs_paths.sh SOURCE_DIR
set -euo pipefail
cd "$1"
if grep -rnE '\.\./shared|/work/|/tmp/' --include='*.md' README.md CONTRIBUTING.md docs examples; then
  echo "docs_paths: the lines above cite a path outside the repository" >&2
  exit 1
fi
echo "docs_paths: no path outside the repository"

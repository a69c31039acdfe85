#!/usr/bin/env bash
# Fails when a C or C++ file differs from what clang-format (with .clang-format) makes of it.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.h' '*.cc' '*.c' 2>/dev/null || find sdk encoder tests bench tools examples -name '*.h' -o -name '*.cc' -o -name '*.c')
clang-format --dry-run -Werror $files
echo "format: $(echo "$files" | wc -w) files clean"

#!/usr/bin/env bash
# Checks the C++ sources against the repository's .clang-format (tabs for indentation, Allman
# braces, 100 columns): lists every file whose formatting differs and exits 1 if there is one.
# Usage: scripts/check_format.sh [--fix] [files...]
#   --fix   reformat the differing files in place (clang-format -i) instead of failing
#   files   check only these (default: every *.cpp, *.h, *.hpp, *.cc tracked by git, or found
#           under apps bench fuzz libs tests outside a git checkout)
# Environment: CLANG_FORMAT (default clang-format). Formatting differs between clang-format
# versions: the reference is the version of Debian 12 (clang-format 14); doc/building.md.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
CF="${CLANG_FORMAT:-clang-format}"
fix=0
if [[ "${1:-}" == "--fix" ]]; then
	fix=1
	shift
fi
if ! command -v "$CF" >/dev/null 2>&1; then
	echo "check_format: $CF not found (apt-get install clang-format, or set CLANG_FORMAT)" >&2
	exit 2
fi
cd "$ROOT"
files=()
if [[ $# -gt 0 ]]; then
	files=("$@")
elif git -C "$ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
	while IFS= read -r -d '' f; do [[ -f "$f" ]] && files+=("$f"); done \
		< <(git ls-files -z -- '*.cpp' '*.h' '*.hpp' '*.cc')
else
	while IFS= read -r -d '' f; do files+=("$f"); done \
		< <(find apps bench fuzz libs tests -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.hpp' \
			-o -name '*.cc' \) -print0 2>/dev/null | sort -z)
fi
differ=()
for f in "${files[@]}"; do
	if ! "$CF" --style=file "$f" | cmp -s - "$f"; then differ+=("$f"); fi
done
if [[ ${#differ[@]} -eq 0 ]]; then
	echo "check_format: ${#files[@]} files, all formatted ($("$CF" --version))"
	exit 0
fi
if [[ $fix -eq 1 ]]; then
	"$CF" -i --style=file "${differ[@]}"
	printf 'check_format: reformatted %s\n' "${differ[@]}"
	echo "check_format: reformatted ${#differ[@]} of ${#files[@]} files"
	exit 0
fi
printf '%s\n' "${differ[@]}"
echo "check_format: ${#differ[@]} of ${#files[@]} files differ from .clang-format" \
	"(scripts/check_format.sh --fix reformats them)" >&2
exit 1

#!/usr/bin/env bash
# Fail, listing them, if any C or C++ source of the project is not formatted per .clang-format.
#
#   run_clang_format.sh SOURCE_DIR [CLANG_FORMAT]
#
# Checks *.cpp *.hpp *.c *.h under daemon/ clients/ drivers/ idl/include idl/wire tests/ bench/
# examples/.
# Files come from git (tracked plus untracked-not-ignored) when SOURCE_DIR is a git work tree,
# else from find. Fix with: clang-format -i FILE...
set -euo pipefail

src=${1:?usage: $0 SOURCE_DIR [CLANG_FORMAT]}
clang_format=${2:-${CLANG_FORMAT:-clang-format}}
command -v "$clang_format" >/dev/null || { echo "SKIP: $clang_format not found" >&2; exit 77; }
cd "$src"

dirs=()
for d in daemon clients drivers idl/include idl/wire tests bench examples; do [[ -d $d ]] && dirs+=("$d"); done
((${#dirs[@]} > 0)) || { echo "no source directories"; exit 0; }

if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- "${dirs[@]}" |
    grep -E '\.(cpp|hpp|c|h)$' | sort -u | while read -r f; do [[ -f $f ]] && echo "$f"; done)
else
  mapfile -t files < <(find "${dirs[@]}" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' \) | sort)
fi
((${#files[@]} > 0)) || { echo "no files to check"; exit 0; }

mapfile -t bad < <(printf '%s\0' "${files[@]}" |
  xargs -0 -n 8 -P "$(nproc)" sh -c 'for f; do "$0" --dry-run -Werror "$f" >/dev/null 2>&1 || echo "$f"; done' \
    "$clang_format" | sort)

"$clang_format" --version
if ((${#bad[@]} > 0)); then
  echo "${#bad[@]} of ${#files[@]} files are not clang-formatted:"
  printf '  %s\n' "${bad[@]}"
  echo "first differences (${bad[0]}):"
  "$clang_format" "${bad[0]}" | diff -u --label "${bad[0]}" --label "${bad[0]} (clang-format)" "${bad[0]}" - | head -n 40 || true
  echo "fix with: (cd $src && $clang_format -i ${bad[*]})"
  exit 1
fi
echo "ok: ${#files[@]} files formatted"

#!/usr/bin/env bash
# The format check: every C++ line changed since the house style was adopted (the commit that added
# .clang-format), or since BASE when given, is as clang-format writes it. Lines nobody has touched
# since keep their hand formatting, so adopting the style did not rewrite the tree.
#   scripts/check_format.sh [--fix] [BASE]     --fix: format those lines in place
# Exit 0 clean, 1 with the differences printed, 77 when it cannot judge (no git history or no
# clang-format-diff: the test sculpt.format is then skipped).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
fix=() base=""
for a in "$@"; do
  case "$a" in
    --fix) fix=(-i) ;;
    *) base="$a" ;;
  esac
done
diff_tool=$(command -v clang-format-diff || command -v clang-format-diff-14 || true)
if [ -z "$diff_tool" ] || ! git rev-parse --git-dir > /dev/null 2>&1; then
  echo "check_format: skipped (needs git history and clang-format-diff, Debian: clang-format)"
  exit 77
fi
if [ -z "$base" ]; then
  base=$(git log --diff-filter=A --format=%H -1 -- .clang-format)
  # Not yet committed: the working tree's changes against HEAD.
  [ -n "$base" ] || base=HEAD
  [ "$base" = HEAD ] || base="$base~1"
fi
# The working tree against base: committed and uncommitted changes alike.
out=$(git diff -U0 --no-color "$base" -- '*.cpp' '*.hpp' | "$diff_tool" -p1 "${fix[@]}")
# New files git does not track yet: all their lines.
while IFS= read -r f; do
  if ((${#fix[@]})); then
    clang-format -i "$f"
  else
    out+=$(clang-format "$f" | diff -u --label "$f" --label "$f (formatted)" "$f" - || true)
  fi
done < <(git ls-files --others --exclude-standard -- '*.cpp' '*.hpp')
if [ -n "$out" ]; then
  printf '%s\n' "$out"
  echo "check_format: the lines above are not as clang-format writes them (scripts/check_format.sh --fix formats them)"
  exit 1
fi
echo "check_format: every C++ line changed since $(git rev-parse --short "$base") is formatted"

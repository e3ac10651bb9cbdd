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
# The working tree against base: committed and uncommitted changes alike, one file's part at a time.
# A file whose changed lines were found formatted before (the same file, lines, .clang-format and
# clang-format) is not formatted again: clang-format-diff costs about 60 ms a file (most of it
# starting clang-format), and the test runs in both suites of every CI run.
cache="${XDG_CACHE_HOME:-$HOME/.cache}/sculpt/check_format"
mkdir -p "$cache" 2> /dev/null || cache=""
parts=$(mktemp -d)
trap 'rm -rf "$parts"' EXIT
git diff -U0 --no-color "$base" -- '*.cpp' '*.hpp' |
  awk -v dir="$parts" '/^diff --git / { n++; f = sprintf("%s/%05d", dir, n) } n { print > f }'
# "part key" for each file's part, computed in one process (a few per file cost seconds).
keyed=$(
  python3 - "$parts" "$(clang-format --version)" << 'PY'
import hashlib, os, sys
parts, version = sys.argv[1], sys.argv[2]
salt = version.encode() + open(".clang-format", "rb").read()
for name in sorted(os.listdir(parts)):
    part = open(os.path.join(parts, name), "rb").read()
    files = [l[6:] for l in part.decode(errors="replace").splitlines() if l.startswith("+++ b/")]
    if files and os.path.isfile(files[0]):
        print(os.path.join(parts, name), hashlib.sha1(salt + part + open(files[0], "rb").read()).hexdigest())
PY
)
todo=() keys=()
while read -r part key; do
  [ -n "$part" ] || continue
  if ((${#fix[@]} == 0)) && [ -n "$cache" ] && [ -e "$cache/$key" ]; then continue; fi
  todo+=("$part") keys+=("$key")
done <<< "$keyed"
out=""
((${#todo[@]} == 0)) || out=$(cat "${todo[@]}" | "$diff_tool" -p1 "${fix[@]}")
# Files clang-format-diff had nothing to say about are formatted: remember them.
if ((${#fix[@]} == 0)) && [ -n "$cache" ]; then
  for i in "${!todo[@]}"; do
    file=$(sed -n 's/^+++ b\///p' "${todo[$i]}" | head -n 1)
    # clang-format-diff names a file it would change as "--- FILE<tab>(before formatting)".
    grep -qF -- "--- $file"$'\t' <<< "$out" || touch "$cache/${keys[$i]}"
  done
fi
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

#!/usr/bin/env bash
# Byte-for-byte check of what rockbench writes, wall times aside: every shipped scene's `run`
# and `compare --engines all` folder and every shipped study's members.csv and study.json.
# A refactoring records the outputs before and checks them after:
#   scripts/check-outputs.sh record DIR     run everything, keep the normalised files in DIR
#   scripts/check-outputs.sh check DIR      run everything again and compare with DIR
# Options (environment): ROCKBENCH_BIN (default build/src/cli/rockbench), ONLY=scenes|studies,
# JOBS (study workers, default 2), COMPARE_ARGS (extra arguments of every compare, e.g. "--quick":
# the comparisons without perturbation members, minutes instead of hours; use the same on both
# sides). Wall-clock figures are replaced by "W" before comparing: JSON
# values whose key contains "wall", "real_time" or "serial_s" (a study's serial part's wall
# time) and an external engine's process measurements (read_s, monitor_s, overhead_s,
# peak_resident_mib), CSV columns whose header contains "wall" or "real_time", wall times printed on stdout
# and stderr, the temporary folder's name. Everything else must be identical. The check
# normalises the recorded copy again, so a figure the normaliser learns later is blanked on both
# sides.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:?"usage: scripts/check-outputs.sh record|check DIR"}
dir=${2:?"usage: scripts/check-outputs.sh record|check DIR"}
bin=${ROCKBENCH_BIN:-build/src/cli/rockbench}
jobs=${JOBS:-2}
case "$mode" in record | check) ;; *) echo "check-outputs.sh: mode must be record or check, not '$mode'" >&2; exit 2 ;; esac
[ -x "$bin" ] || { echo "check-outputs.sh: no program at $bin (build first)" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/rockbench-outputs.XXXXXX")
trap 'rm -rf "$work"' EXIT
out="$work/out"
mkdir -p "$out"

# Wall times out, the rest untouched (JSON re-printed with sorted keys is not wanted: the key
# order is part of the bytes, so the replacement is textual).
normalise() {
  python3 - "$1" <<'EOF'
import csv, io, re, sys
path = sys.argv[1]
text = open(path, encoding="utf-8", errors="surrogateescape").read()
if path.endswith(".json"):
    text = re.sub(r'("[A-Za-z0-9_]*(?:wall|real_time|serial_s)[A-Za-z0-9_]*"\s*:\s*)(-?[0-9.eE+-]+|null)', r'\1"W"', text)
    # An external engine's process measurements (docs/external-engines.md): times and memory.
    text = re.sub(r'("(?:read_s|monitor_s|overhead_s|peak_resident_mib)"\s*:\s*)(-?[0-9.eE+-]+|null)', r'\1"W"', text)
elif path.endswith(".csv"):
    lines = text.split("\n")
    header = next((i for i, l in enumerate(lines) if l and not l.startswith("#")), None)
    if header is not None:
        cols = lines[header].split(",")
        wall = [i for i, c in enumerate(cols) if "wall" in c or "real_time" in c]
        if wall:
            for i in range(header + 1, len(lines)):
                if not lines[i] or lines[i].startswith("#"):
                    continue
                row = next(csv.reader([lines[i]]))
                for j in wall:
                    if j < len(row):
                        row[j] = "W"
                buf = io.StringIO()
                csv.writer(buf, lineterminator="").writerow(row)
                lines[i] = buf.getvalue()
    text = "\n".join(lines)
elif path.endswith(".stdout") or path.endswith(".stderr"):
    # Printed wall times: a run's ", 4.48 ms" at the end of its line (or before ";"), "wall time
    # 0.21 s", and figures after "took"; the temporary output folder's name.
    text = re.sub(r'((?:wall|took|in)[^0-9\n]{0,12})[0-9]+(\.[0-9]+)?( ?(?:s|ms|min)\b)', r'\1W\3', text)
    text = re.sub(r', [0-9.]+(e[+-][0-9]+)? ms(;|\n|$)', r', W ms\2', text)
    text = re.sub(r'/[^ \n]*/out/', 'OUT/', text)
open(path, "w", encoding="utf-8", errors="surrogateescape").write(text)
EOF
}

run_case() {  # name, then the command's arguments (its output folder is $out/$name)
  local name=$1
  shift
  local rc=0
  "$bin" "$@" --out "$out/$name" >"$out/$name.stdout" 2>"$out/$name.stderr" || rc=$?
  echo "$rc" >"$out/$name.rc"
  echo "  $name: exit $rc"
}

echo "check-outputs: $mode with $bin"
if [ "${ONLY:-all}" != studies ]; then
  for scene in scenes/*.toml; do
    name=$(basename "$scene" .toml)
    run_case "run_$name" run "$scene"
    # shellcheck disable=SC2086 # COMPARE_ARGS is a list of arguments
    run_case "compare_$name" compare "$scene" --engines all ${COMPARE_ARGS:-}
  done
fi
if [ "${ONLY:-all}" != scenes ]; then
  for study in scenes/studies/*.toml; do
    name=$(basename "$study" .toml)
    grep -q '^\[\[axis\]\]' "$study" || continue  # a study's scene, not a study
    run_case "study_$name" ensemble "$study" --jobs "$jobs"
    # A study folder's report material is members.csv and study.json; members/ only with
    # --keep-histories.
    find "$out/study_$name" -mindepth 1 -maxdepth 1 ! -name members.csv ! -name study.json \
      -exec rm -rf {} + 2>/dev/null || true
  done
fi

# Normalise, then record or compare.
while IFS= read -r -d '' f; do normalise "$f"; done < <(find "$out" -type f \( -name '*.json' -o -name '*.csv' -o -name '*.stdout' -o -name '*.stderr' \) -print0)
if [ "$mode" = record ]; then
  rm -rf "$dir"
  mkdir -p "$(dirname "$dir")"
  mv "$out" "$dir"
  (cd "$dir" && find . -type f | sort | xargs sha256sum) >"$dir.sha256"
  echo "check-outputs: recorded $(wc -l <"$dir.sha256") files in $dir"
else
  cp -r "$dir" "$work/recorded"
  # ONLY=scenes or ONLY=studies compares that part alone.
  case "${ONLY:-all}" in
    scenes) rm -rf "$work/recorded"/study_* ;;
    studies) rm -rf "$work/recorded"/run_* "$work/recorded"/compare_* ;;
  esac
  while IFS= read -r -d '' f; do normalise "$f"; done < <(find "$work/recorded" -type f \( -name '*.json' -o -name '*.csv' -o -name '*.stdout' -o -name '*.stderr' \) -print0)
  if diff -r "$work/recorded" "$out" >"$work/diff.txt"; then
    echo "check-outputs: identical ($(find "$out" -type f | wc -l) files)"
  else
    echo "check-outputs: DIFFERENT (the whole diff: $dir.diff):"
    { diff -rq "$work/recorded" "$out" || true; } | sed "s|$work/||g"
    cp "$work/diff.txt" "$dir.diff"
    head -60 "$work/diff.txt"
    exit 1
  fi
fi

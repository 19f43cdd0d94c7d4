#!/usr/bin/env bash
# Fuzzing with libFuzzer (docs/fuzzing.md): builds the fuzz targets of tests/fuzz/ with clang
# (ASan + UBSan + libFuzzer) in their own build folder, then runs them.
#   scripts/fuzz.sh --ci            the short deterministic run (CI: the test fuzz_short): every
#                                   target for a fixed number of runs from a fixed seed, capped
#                                   in seconds; exit 1 on any finding
#   scripts/fuzz.sh --minutes N     a campaign: every target N minutes (nice -n 10, one process),
#                                   carrying on past findings; the corpus grows in BUILD/corpus/
#   scripts/fuzz.sh --coverage      (with either) then measures what the corpus covers: libFuzzer's
#                                   edges and features, and clang's source-based line coverage
#                                   (llvm-cov) in a second build, BUILD-cov
#   scripts/fuzz.sh --update-corpus merges BUILD/corpus/<t> into tests/fuzz/corpus/<t>: only the
#                                   inputs that add coverage to the committed and shipped seeds
# Other options: --targets a,b (default: all of tests/fuzz/targets.txt), --runs N, --seconds S
# (the short run's cap per target, 60), --seed N (1), --build-dir DIR (build-fuzz), --jobs N (2).
# Findings (crash-*, timeout-*, oom-*, leak-*) are written to BUILD/findings/<target>/; the
# summary names each with its first line of explanation. Exit: 0 no finding, 1 findings,
# 2 usage or build error, 77 clang's libFuzzer is missing (said on stderr).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

mode=""
minutes=0
coverage=0
update_corpus=0
targets=""
runs=""
seconds=""
seed=1
build_dir=build-fuzz
jobs=2
usage() { sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    --ci) mode=ci ;;
    --minutes) mode=campaign; minutes=$2; shift ;;
    --coverage) coverage=1 ;;
    --update-corpus) update_corpus=1 ;;
    --targets) targets=$2; shift ;;
    --runs) runs=$2; shift ;;
    --seconds) seconds=$2; shift ;;
    --seed) seed=$2; shift ;;
    --build-dir) build_dir=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "fuzz.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
if [ -z "$mode" ] && [ "$coverage" = 0 ] && [ "$update_corpus" = 0 ]; then
  usage >&2
  exit 2
fi
case "$build_dir" in /*) ;; *) build_dir=$root/$build_dir ;; esac

# The clang of Debian 12 and its libFuzzer (clang-14, libclang-rt-14-dev); ROCKBENCH_FUZZ_CLANG
# (a clang, with its clang++ beside it) chooses another.
if [ -n "${ROCKBENCH_FUZZ_CLANG:-}" ]; then
  clangc=$(command -v "$ROCKBENCH_FUZZ_CLANG" || true)
  clangxx=$(command -v "${ROCKBENCH_FUZZ_CLANG/clang/clang++}" || true)
else
  clangxx=$(command -v clang++-14 || command -v clang++ || true)
  clangc=$(command -v clang-14 || command -v clang || true)
fi
if [ -z "$clangxx" ] || [ -z "$clangc" ]; then
  echo "fuzz.sh: LEFT OUT: clang++ not found; install the Debian packages clang-14 and" \
       "libclang-rt-14-dev (scripts/install-deps.sh). No fuzzing was done." >&2
  exit 77
fi
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf '#include <cstddef>\n#include <cstdint>\nextern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }\n' >"$probe/p.cc"
if ! "$clangxx" -fsanitize=fuzzer,address,undefined "$probe/p.cc" -o "$probe/p" 2>"$probe/err"; then
  echo "fuzz.sh: LEFT OUT: $clangxx cannot link -fsanitize=fuzzer,address,undefined; install the" \
       "Debian package libclang-rt-14-dev (scripts/install-deps.sh). No fuzzing was done." >&2
  sed 's/^/  /' "$probe/err" | head -5 >&2
  exit 77
fi
llvm_suffix=""
case "$clangxx" in *-14) llvm_suffix=-14 ;; esac

# Targets: name, dictionary, shipped seeds.
declare -A dict_of seeds_of
all_targets=()
while read -r name dict seeds; do
  case "$name" in ''|'#'*) continue ;; esac
  all_targets+=("$name")
  dict_of[$name]=$dict
  seeds_of[$name]=$seeds
done <tests/fuzz/targets.txt
if [ -n "$targets" ]; then
  IFS=, read -r -a chosen <<<"$targets"
  for t in "${chosen[@]}"; do
    [ -n "${dict_of[$t]:-}" ] || { echo "fuzz.sh: unknown target $t (tests/fuzz/targets.txt)" >&2; exit 2; }
  done
else
  chosen=("${all_targets[@]}")
fi

# Per target: longest input (bytes) and the time (s) past which one input is a hang. A scene run
# is a simulation (scene_run_fuzz.cc bounds what it runs); 60 s under ASan is about 20 s of a
# release build for at most 30 simulated seconds.
# Campaigns allow longer inputs (libFuzzer grows lengths as coverage asks): a header line of
# tens of kB is what overflowed std::regex's stack in the AT2 reader (docs/fuzzing.md).
max_len_of() {
  if [ "$mode" = campaign ]; then
    case "$1" in record_*) echo 131072 ;; *) echo 16384 ;; esac
  else
    case "$1" in record_*) echo 8192 ;; *) echo 4096 ;; esac
  fi
}
timeout_of() { case "$1" in scene_run) echo 60 ;; *) echo 10 ;; esac; }
rss_limit_mb=2048

# configure_and_build DIR FLAGS TARGET...: a clang build of the project with only what the fuzz
# targets need (no engine, renderer, MPI, benchmark), the fuzz targets built with libFuzzer.
configure_and_build() {
  local dir=$1 flags=$2
  shift 2
  local gen=()
  command -v ninja >/dev/null && [ ! -f "$dir/Makefile" ] && gen=(-G Ninja)
  CC=$clangc CXX=$clangxx cmake -S "$root" -B "$dir" "${gen[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1" "-DCMAKE_CXX_FLAGS=$flags" \
    -DROCKBENCH_FUZZ_LIBFUZZER=ON -DROCKBENCH_BUILD_TESTS=ON -DROCKBENCH_BUILD_BENCH=OFF \
    -DROCKBENCH_WITH_ODE=OFF -DROCKBENCH_WITH_MUJOCO=OFF \
    -DROCKBENCH_WITH_DART=OFF -DROCKBENCH_WITH_SICONOS=OFF -DROCKBENCH_WITH_OSMESA=OFF \
    -DROCKBENCH_WITH_MPI=OFF >"$dir/fuzz-configure.log" 2>&1 ||
    { echo "fuzz.sh: configuring $dir failed (see $dir/fuzz-configure.log)" >&2; tail -20 "$dir/fuzz-configure.log" >&2; exit 2; }
  local exes=()
  for t in "$@"; do exes+=("fuzz_$t"); done
  nice -n 10 cmake --build "$dir" -j"$jobs" --target "${exes[@]}" >"$dir/fuzz-build.log" 2>&1 ||
    {
      echo "fuzz.sh: building $dir failed (see $dir/fuzz-build.log)" >&2
      grep -m20 -E "error|Error|undefined reference" "$dir/fuzz-build.log" >&2
      grep -q "fuzz_study_reader.*undefined reference\|undefined reference" "$dir/fuzz-build.log" &&
        echo "fuzz.sh: an undefined reference in fuzz_study_reader: add the harness source that" \
             "defines it to ROCKBENCH_FUZZ_STUDY_SOURCES in tests/fuzz/CMakeLists.txt" >&2
      exit 2
    }
}

# seed_dirs T: the folders libFuzzer reads T's seeds from: the committed corpus, the fixed
# findings, and a folder of links to the shipped seed files (none copied). The short CI run of
# scene_run leaves its committed corpus out: each of its 680 inputs is a simulation (0.2 s under
# ASan, 136 s in all, before a single new input), and the tests fuzz_replay_scene_run replay
# that corpus in the normal and the sanitizer builds anyway.
seed_dirs() {
  local t=$1 dirs=()
  for d in tests/fuzz/corpus/$t tests/fuzz/regressions/$t; do
    if [ "$mode" = ci ] && [ "$t" = scene_run ] && [ "$d" = "tests/fuzz/corpus/$t" ]; then
      continue
    fi
    [ -d "$d" ] && dirs+=("$root/$d")
  done
  local spec=${seeds_of[$t]}
  if [ "$spec" != "-" ]; then
    local shipped=$build_dir/seeds/$t
    rm -rf "$shipped"
    mkdir -p "$shipped"
    local folder=${spec%%/\**} suffix=${spec##*\*}
    for f in "$root/$folder"/*"$suffix"; do ln -s "$f" "$shipped/$(basename "$f")"; done
    dirs+=("$shipped")
  fi
  echo "${dirs[@]}"
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-symbolize=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
command -v "llvm-symbolizer$llvm_suffix" >/dev/null &&
  export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v "llvm-symbolizer$llvm_suffix")}

# The last "cov: E ft: F corp: C" libFuzzer printed, and its run count.
stats_line() {
  local log=$1
  local cov ft corp execs
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo "?")
  ft=$(grep -oE 'ft: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo "?")
  corp=$(grep -oE 'corp: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo "?")
  execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || true)
  [ -n "$execs" ] || execs=$(grep -oE '^#[0-9]+' "$log" | tail -1 | tr -d '#' || echo "?")
  echo "runs $execs, edges (cov) $cov, features (ft) $ft, corpus $corp"
}

findings_total=0
report_findings() {
  local t=$1 dir=$2
  local n=0
  for f in "$dir"/crash-* "$dir"/timeout-* "$dir"/oom-* "$dir"/leak-*; do
    [ -e "$f" ] || continue
    n=$((n + 1))
    echo "  finding: $f"
  done
  findings_total=$((findings_total + n))
  echo "  findings: $n"
}

if [ -n "$mode" ] || [ "$update_corpus" = 1 ]; then
  mkdir -p "$build_dir"
  t0=$(date +%s)
  configure_and_build "$build_dir" \
    "-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -gline-tables-only" \
    "${chosen[@]}"
  echo "fuzz.sh: built ${#chosen[@]} targets in $build_dir ($(($(date +%s) - t0)) s)"
fi

fixed_addresses=()
setarch "$(uname -m)" -R true 2>/dev/null && fixed_addresses=(setarch "$(uname -m)" -R)
if [ -n "$mode" ]; then
  for t in "${chosen[@]}"; do
    exe=$build_dir/tests/fuzz/fuzz_$t
    findings=$build_dir/findings/$t
    mkdir -p "$findings" "$build_dir/logs"
    log=$build_dir/logs/$t.log
    read -r -a seeds <<<"$(seed_dirs "$t")"
    common=(-seed="$seed" -timeout="$(timeout_of "$t")" -rss_limit_mb=$rss_limit_mb
            -max_len="$(max_len_of "$t")" -dict="$root/tests/fuzz/dict/${dict_of[$t]}"
            -artifact_prefix="$findings/" -print_final_stats=1)
    t1=$(date +%s)
    if [ "$mode" = ci ]; then
      # Deterministic: a fresh working corpus, a fixed seed and run count (the cap in seconds is
      # only a guard), and no address randomisation (some code paths, e.g. containers ordered by
      # address, differ with the addresses: the same seed then finds other inputs).
      work=$build_dir/ci-corpus/$t
      rm -rf "$work"
      mkdir -p "$work"
      n=${runs:-}
      [ -n "$n" ] || case "$t" in scene_run) n=30000 ;; record_*) n=8000 ;; study_reader) n=3000 ;; members_resume) n=5000 ;; *) n=20000 ;; esac
      rc=0
      "${fixed_addresses[@]}" "$exe" "${common[@]}" -runs="$n" -max_total_time="${seconds:-60}" "$work" "${seeds[@]}" \
        >"$log" 2>&1 || rc=$?
    else
      # A campaign: one process at a time (-fork=1, the 2 shared cores), going on past findings.
      work=$build_dir/corpus/$t
      mkdir -p "$work"
      rc=0
      nice -n 10 "$exe" "${common[@]}" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
        -max_total_time=$((minutes * 60)) "$work" "${seeds[@]}" >"$log" 2>&1 || rc=$?
    fi
    echo "fuzz $t: $(stats_line "$log"), $(($(date +%s) - t1)) s, exit $rc (log: $log)"
    report_findings "$t" "$findings"
    if [ "$rc" != 0 ] && ! ls "$findings"/{crash,timeout,oom,leak}-* >/dev/null 2>&1; then
      echo "  libFuzzer failed without a finding file:" >&2
      tail -20 "$log" >&2
      findings_total=$((findings_total + 1))
    fi
  done
fi

if [ "$coverage" = 1 ]; then
  # libFuzzer's edges and features: the fuzz build run once over each target's corpus (the
  # working corpus of the last runs, and the seeds). Source-based line and branch coverage: the
  # same targets without sanitizers, instrumented for llvm-cov, over the same inputs.
  cov_dir=$build_dir-cov
  mkdir -p "$cov_dir"
  configure_and_build "$cov_dir" "-fprofile-instr-generate -fcoverage-mapping" "${chosen[@]}"
  profdata=$(command -v "llvm-profdata$llvm_suffix" || true)
  llvmcov=$(command -v "llvm-cov$llvm_suffix" || true)
  for t in "${chosen[@]}"; do
    read -r -a seeds <<<"$(seed_dirs "$t")"
    dirs=()
    for d in "$build_dir/corpus/$t" "$build_dir/ci-corpus/$t"; do [ -d "$d" ] && dirs+=("$d"); done
    opts=(-runs=0 -timeout="$(timeout_of "$t")" -rss_limit_mb=$rss_limit_mb -max_len="$(max_len_of "$t")")
    n_inputs=$(find "${dirs[@]}" "${seeds[@]}" -maxdepth 1 \( -type f -o -type l \) ! -name .gitkeep | wc -l)
    edges="?"
    if [ -x "$build_dir/tests/fuzz/fuzz_$t" ]; then
      "$build_dir/tests/fuzz/fuzz_$t" "${opts[@]}" "${dirs[@]}" "${seeds[@]}" >"$cov_dir/$t.edges.log" 2>&1 || true
      edges=$(grep -oE 'INITED cov: [0-9]+ ft: [0-9]+' "$cov_dir/$t.edges.log" | head -1 | sed 's/INITED //')
    fi
    echo "coverage $t: $n_inputs inputs; libFuzzer (ASan build): ${edges:-?}"
    exe=$cov_dir/tests/fuzz/fuzz_$t
    rm -f "$cov_dir/$t".profraw
    LLVM_PROFILE_FILE="$cov_dir/$t.profraw" "$exe" "${opts[@]}" "${dirs[@]}" "${seeds[@]}" \
      >"$cov_dir/$t.log" 2>&1 || true
    if [ -z "$profdata" ] || [ -z "$llvmcov" ]; then
      echo "  line coverage left out: llvm-profdata/llvm-cov not found (Debian: llvm-14)"
      continue
    fi
    "$profdata" merge -sparse "$cov_dir/$t.profraw" -o "$cov_dir/$t.profdata"
    # The project's sources only (not toml++, the standard library or the target itself).
    "$llvmcov" report "$exe" -instr-profile="$cov_dir/$t.profdata" \
      -ignore-filename-regex='(/usr/|tests/fuzz/)' >"$cov_dir/$t.cov.txt"
    # Columns: file, regions (3), functions (3), lines: total, missed, cover, branches: the same.
    awk '
      function row(name) {
        printf "  %-32s lines %5d of %5d (%s), branches %4d of %4d (%s)\n", name, $8 - $9, $8, $10,
               $11 - $12, $11, $13
      }
      $1 == "TOTAL" { row("all sources it links") }
      $1 ~ /(scene|records|ground_motion|study|simulate|impact|transitions|intensity|synthetic_motion)\.cc$/ { row($1) }
    ' "$cov_dir/$t.cov.txt"
  done
fi

if [ "$update_corpus" = 1 ]; then
  # Only what adds coverage to what is already committed or shipped.
  for t in "${chosen[@]}"; do
    [ -d "$build_dir/corpus/$t" ] || { echo "update-corpus $t: no campaign corpus in $build_dir/corpus/$t"; continue; }
    read -r -a seeds <<<"$(seed_dirs "$t")"
    merged=$build_dir/merge/$t
    rm -rf "$merged"
    mkdir -p "$merged"
    for d in "${seeds[@]}"; do cp -L "$d"/* "$merged"/ 2>/dev/null || true; done
    rm -f "$merged"/.gitkeep "$merged"/README.md
    before=$(ls "$merged" | sort)
    "$build_dir/tests/fuzz/fuzz_$t" -merge=1 -timeout="$(timeout_of "$t")" \
      -rss_limit_mb=$rss_limit_mb -max_len="$(max_len_of "$t")" "$merged" "$build_dir/corpus/$t" \
      >"$build_dir/logs/$t.merge.log" 2>&1
    added=0
    mkdir -p "tests/fuzz/corpus/$t"
    for f in $(comm -13 <(echo "$before") <(ls "$merged" | sort)); do
      cp "$merged/$f" "tests/fuzz/corpus/$t/$f"
      added=$((added + 1))
    done
    echo "update-corpus $t: $added inputs added to tests/fuzz/corpus/$t"
  done
fi

if [ -n "$mode" ]; then
  if [ "$findings_total" -gt 0 ]; then
    echo "fuzz.sh: $findings_total finding(s); reproduce one with: $build_dir/tests/fuzz/fuzz_<target> FILE"
    exit 1
  fi
  echo "fuzz.sh: no finding"
fi

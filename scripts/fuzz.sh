#!/usr/bin/env bash
# Fuzzes the C modelDescription reader with libFuzzer under AddressSanitizer and UBSan for a
# bounded time (FUZZ_SECONDS, default 90), then the plan reader (PLAN_FUZZ_SECONDS, default 60,
# seeded with tests/fuzz/plan_seeds, plans the writer wrote). The corpus is seeded at run time with the
# modelDescriptions of the FMUs built in build/release and of the Reference FMUs (when their
# folder is found), plus every committed crash in tests/fuzz/crashes. A crash fails this script
# and leaves its input in build/fuzz/artifacts: copy it into tests/fuzz/crashes, where
# `meson test` replays it ever after.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
seconds=${FUZZ_SECONDS:-90}
out=build/fuzz
mkdir -p "$out/artifacts"
rm -rf "$out/corpus" && mkdir -p "$out/corpus"

clang -g -O1 -std=c11 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
  -Isrc/include -Isrc/fmu/description -Isrc/support tests/fuzz/model_description_fuzz.c \
  src/fmu/description/model_description.c src/fmu/description/string_store.c \
  src/fmu/description/xml_tokenizer.c src/support/array.c \
  -o "$out/model_description_fuzz"

# seeds: every modelDescription.xml in the FMUs we build and in the Reference FMUs
reference=${SYSSIMX_REFERENCE_FMUS:-$root/../shared/reference-fmus}
python3 - "$out/corpus" build/release build/dev "$reference" <<'PY'
import hashlib, sys, zipfile
from pathlib import Path
corpus, folders = Path(sys.argv[1]), [Path(f) for f in sys.argv[2:]]
count = 0
for folder in folders:
    for fmu in sorted(folder.rglob("*.fmu")) if folder.is_dir() else []:
        try:
            with zipfile.ZipFile(fmu) as archive:
                data = archive.read("modelDescription.xml")
        except (OSError, KeyError, zipfile.BadZipFile):
            continue
        (corpus / hashlib.sha1(data).hexdigest()).write_bytes(data)
        count += 1
print(f"fuzz: {count} modelDescriptions seeded the corpus")
PY
cp tests/fuzz/crashes/* "$out/corpus/"

# -max_len: the largest seed decides it otherwise; 64 KB reaches past every buffer's first growth
if ! "$out/model_description_fuzz" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$out/artifacts/" \
  "$out/corpus" >"$out/fuzz.log" 2>&1; then
  tail -n 60 "$out/fuzz.log" >&2
  echo "fuzz: the modelDescription reader crashed; the input is in $out/artifacts" >&2
  exit 1
fi
grep -E "^(Done|stat::number_of_executed_units|stat::peak_rss_mb)" "$out/fuzz.log" || true

# the plan reader: its seeds, then the same bounded run
plan_seconds=${PLAN_FUZZ_SECONDS:-60}
rm -rf "$out/plan_corpus" && mkdir -p "$out/plan_corpus"
# the plan's words (event sources, localization methods) are the engine's own tables, so the
# fuzzer is linked with the engine's sources and include folders as src/meson.build lists them
mapfile -t engine_flags < <(python3 - <<'PY'
import os
import re
from pathlib import Path
import fmpy
print("-isystem")
print(os.path.join(os.path.dirname(fmpy.__file__), "c-code"))  # the FMI headers, as meson.build
text = Path("src/meson.build").read_text()
sources = re.search(r"engine_sources = files\((.*?)\)", text, re.S).group(1)
folders = re.search(r"engine_private_inc = include_directories\((.*?)\)", text, re.S).group(1)
for folder in re.findall(r"'([^']+)'", folders):
    print(f"-Isrc/{folder}")
for source in re.findall(r"'([^']+\.c)'", sources):
    print(f"src/{source}")
PY
)
clang -g -O1 -std=c11 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -pthread \
  tests/fuzz/plan_fuzz.c "${engine_flags[@]}" -l:libsundials_cvode.a -l:libsundials_nvecserial.a \
  -l:libsundials_sunmatrixdense.a -l:libsundials_sunlinsoldense.a \
  -l:libsundials_sunnonlinsolnewton.a -l:libsundials_generic.a -ldl -lm -o "$out/plan_fuzz"
cp tests/fuzz/plan_seeds/* "$out/plan_corpus/"
if ! "$out/plan_fuzz" -max_total_time="$plan_seconds" -max_len=65536 -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$out/artifacts/plan-" \
  "$out/plan_corpus" >"$out/plan_fuzz.log" 2>&1; then
  tail -n 60 "$out/plan_fuzz.log" >&2
  echo "fuzz: the plan reader crashed; the input is in $out/artifacts (copy it into" \
    "tests/fuzz/plan_seeds)" >&2
  exit 1
fi
grep -E "^(Done|stat::number_of_executed_units|stat::peak_rss_mb)" "$out/plan_fuzz.log" || true

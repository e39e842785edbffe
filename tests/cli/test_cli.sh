#!/bin/sh
# Command-line behaviour: help, version, errors with file:line:key and exit code 2, a short run
# with its outputs, the summary line, a clean stop on SIGINT, and every case in cases/ loading.
# usage: test_cli.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
. "$SRC/tests/cli/lib.sh"

expect 0 "usage:" "$RY" --help
expect 0 "ryushi 0" "$RY" --version
expect 2 "unknown command" "$RY" frobnicate
expect 2 "a case file is required" "$RY" run
expect 3 "cannot read" "$RY" run "$T/missing.yaml"

cat > "$T/bad_key.yaml" <<'YAML'
dimension: 2
spacing: 0.01
materials: [{name: water, density: 1000}]
bodies: [{type: box, lo: [0, 0], hi: [0.1, 0.1]}]
scheme: {name: static}
time: {end: 0.1, cfll: 0.3}
YAML
expect 2 "bad_key.yaml:6: unknown key 'time.cfll'" "$RY" run "$T/bad_key.yaml" -o "$T/o1"

sed 's/spacing: 0.01/spacing: -0.01/; s/cfll/cfl/' "$T/bad_key.yaml" > "$T/neg.yaml"
expect 2 "neg.yaml:2: key 'spacing'" "$RY" run "$T/neg.yaml" -o "$T/o2"
expect 2 "key 'spacing': expected a" "$RY" run "$T/neg.yaml" --set spacing=abc -o "$T/o2"
expect 2 "key 'scheme.name'" "$RY" run "$T/neg.yaml" --set spacing=0.01 --set scheme.name=nope
expect 2 "threads" "$RY" run "$T/neg.yaml" --threads 0

# A short run of the seed dam break at 20x40: outputs and the summary line.
"$RY" run "$SRC/cases/dam_break_seed.yaml" -o "$T/run" --set spacing=0.0125 \
    --set time.end=0.02 --set time.output_interval=0.01 > "$T/run.log" 2>&1
rc=$?
[ $rc -eq 0 ] && ok || bad "short run exited $rc: $(cat "$T/run.log")"
for f in dam_break_seed.pvd dam_break_seed_00000.vtp dam_break_seed_00002.vtp series.csv \
    case_resolved.yaml; do
    [ -s "$T/run/$f" ] && ok || bad "missing output $f"
done
tail -n 1 "$T/run.log" | grep -q "^summary status=ok steps=[0-9]* particles=1340 .*wall_s=.*particle_steps_per_s=" \
    && ok || bad "last line is not the summary: $(tail -n 1 "$T/run.log")"
head -n 1 "$T/run/series.csv" | grep -q "^t," && ok || bad "series.csv does not start with t"
ls "$T/run" | grep -q "tmp" && bad "temporary files left in the output" || ok
# The resolved case runs again as it is and gives the same particles.
"$RY" info "$T/run/case_resolved.yaml" | grep -q "particles *1340" && ok \
    || bad "case_resolved.yaml does not reproduce the case"
"$RY" info "$SRC/cases/dam_break_seed.yaml" | grep -q "bytes/particle" && ok || bad "info lacks bytes/particle"
# A non-Newtonian material is reported with its model and values.
"$RY" info "$SRC/cases/mps_giesekus_poiseuille.yaml" \
    | grep -q "Giesekus: solvent nu 0.0001, polymer nu 0.0009 m^2/s, lambda 0.005 s, alpha 0.3" \
    && ok || bad "info does not report the Giesekus material"

# A body that skips its overlaps leaves out the particles half a spacing off an earlier body's
# lattice, which would double the density there: 100 of the second box's 200 stay.
cat > "$T/half.yaml" <<'EOF'
dimension: 2
spacing: 0.01
materials: [{name: water, density: 1000}]
bodies:
  - {type: box, lo: [0, 0], hi: [0.1, 0.1]}
  - {type: box, lo: [0, 0.005], hi: [0.1, 0.205], overlap: skip}
scheme: {name: static}
time: {end: 0.1}
EOF
"$RY" info "$T/half.yaml" | grep -q "particles *200 " && ok \
    || bad "overlap skip half a spacing off: $("$RY" info "$T/half.yaml" 2>&1 | grep particles)"

# time.stop_when: the run ends at the first output whose front lies beyond 0.4 m (about 0.14 s),
# long before time.end, and says so; the rows before it stay below the value.
"$RY" run "$SRC/cases/dam_break_seed.yaml" -o "$T/stop" --threads 1 --set spacing=0.0125 \
    --set time.end=0.5 --set time.output_interval=0.02 --set time.stop_when.quantity=front_x \
    --set time.stop_when.above=0.4 > "$T/stop.log" 2>&1 && ok || bad "stop_when run failed: $(cat "$T/stop.log")"
grep -q "^stopped at t = .*: front_x = .*, above 0.4 (time.stop_when)" "$T/stop.log" && ok \
    || bad "stop_when: no stop line in $(cat "$T/stop.log")"
awk -F, 'NR > 1 { n++; f[n] = $5; t = $1 } END { for (i = 1; i < n; ++i) if (f[i] > 0.4) exit 1;
    exit !(f[n] > 0.4 && t > 0.05 && t < 0.3) }' "$T/stop/series.csv" && ok \
    || bad "stop_when: series does not end at the first row beyond 0.4: $(cut -d, -f1,5 "$T/stop/series.csv")"

# SIGINT: a long run stops cleanly, writes its state and exits 130.
"$RY" run "$SRC/cases/dam_break_seed.yaml" -o "$T/int" --set spacing=0.0125 --set time.dt_max=1e-5 \
    > "$T/int.log" 2>&1 &
pid=$!
sleep 2
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 130 ] && ok || bad "SIGINT run exited $rc: $(tail -n 3 "$T/int.log")"
grep -q "interrupted" "$T/int.log" && ok || bad "no interruption message"
[ -s "$T/int/series.csv" ] && [ -s "$T/int/dam_break_seed.pvd" ] && ok || bad "no output after SIGINT"
ls "$T/int" | grep -q "tmp" && bad "temporary files left after SIGINT" || ok

# Every shipped case loads and sets up (its particles built, its keys valid).
for f in "$SRC"/cases/*.yaml; do
    "$RY" info "$f" > "$T/info.log" 2>&1 && ok || bad "$f does not load: $(tail -n 2 "$T/info.log")"
done

# validate: its help, the list from validation/*.yaml (every manifest with a runner), an unknown
# name
expect 0 "usage: ryushi validate" "$RY" validate --help
# each command's own help: `ryushi help COMMAND` and `ryushi COMMAND --help`
expect 0 "ryushi run CASE \[-o DIR\]" "$RY" help run
expect 0 "ryushi info CASE" "$RY" info --help
expect 0 "ryushi bench \[sph | neighbors\]" "$RY" bench --help
expect 2 "no command 'nope'" "$RY" help nope
expect 0 "^dam_break  *all  *WCSPH dam break" "$RY" validate --list
n=$("$RY" validate --list | wc -l)
m=$(ls "$SRC"/validation/*.yaml | wc -l)
[ "$n" -eq "$m" ] && ok || bad "validate --list shows $n validations, validation/ holds $m"
expect 2 "no validation 'nope'" "$RY" validate nope
# a quick validation records its checks; --report tabulates them with the manifests
"$RY" validate channel --quick -o "$T/val" > "$T/val.log" 2>&1 && ok || bad "validate channel: $(cat "$T/val.log")"
expect 0 "report in $T/val/validation_report.md" "$RY" validate --report -o "$T/val"
grep -q '^| \[channel\](#channel) | quick | 4 | 4 | [0-9.]* s | `ryushi validate channel --quick` |$' "$T/val/validation_report.md" &&
    grep -q '^| time | [0-9.]* s on 1 thread |$' "$T/val/validation_report.md" &&
    grep -q '^| 20 across: outflow against inflow rate (relative) | [0-9.e-]* | 0.03 | PASS |$' "$T/val/validation_report.md" &&
    grep -q '^| \[dam_break\](#dam_break) | not run |' "$T/val/validation_report.md" && ok ||
    bad "validation report: $(cat "$T/val/validation_report.md")"
# --into FILE: the same tables between the report's markers in FILE, the rest of FILE kept
printf 'before\n<!-- ryushi validate --report: begin -->\nold\n<!-- ryushi validate --report: end -->\nafter\n' > "$T/doc.md"
expect 0 "report written into $T/doc.md" "$RY" validate --report -o "$T/val" --into "$T/doc.md"
[ "$(head -n 2 "$T/doc.md" | tail -n 1)" = "<!-- ryushi validate --report: begin -->" ] &&
    [ "$(tail -n 1 "$T/doc.md")" = "after" ] && ! grep -q '^old$' "$T/doc.md" &&
    grep -q '^| 20 across: outflow against inflow rate (relative) | [0-9.e-]* | 0.03 | PASS |$' "$T/doc.md" &&
    ok || bad "validate --into: $(cat "$T/doc.md")"
echo "no markers" > "$T/plain.md"
expect 2 "has no lines '<!-- ryushi validate --report: begin -->'" "$RY" validate --report -o "$T/val" --into "$T/plain.md"
expect 2 "goes with --report" "$RY" validate channel --into "$T/doc.md"
# a validation given as data alone (validation/README.md, "Runs as data"): the seed's dam break
# at 20 x 40 to 0.05 s, the fluid's mass from 0.02 s on against 125 kg/m; and the same held to
# a wrong mass fails
mkdir -p "$T/proj/validation"
ln -s "$SRC/cases" "$T/proj/cases"
cat > "$T/proj/validation/mini.yaml" <<'YAML'
name: mini
summary: "the dam break's mass"
order: 1
tolerances:
  mass: 1.0e-9
runs:
  - name: mini_db
    heading: "the seed's dam break at 20 x 40"
    case: cases/dam_break_seed.yaml
    set: [spacing=0.0125, time.end=0.05, output.vtk=false]
    label: "20 x 40"
    what: "20 x 40: fluid mass against 125 kg/m"
    column: mass
    from: 0.02
    expect: 125
    tolerance: mass
    figure: m
figures:
  - name: m
    file: mini.png
    title: "mass"
    y: "kg/m"
YAML
expect 0 "20 x 40: fluid mass against 125 kg/m  *PASS" "$RY" validate mini --quick --root "$T/proj" -o "$T/mini"
[ -f "$T/mini/mini.png" ] && grep -q '^"20 x 40: fluid mass against 125 kg/m",0,1e-09,PASS$' "$T/mini/results_mini.csv" &&
    ok || bad "data-only validation: $(ls "$T/mini"; cat "$T/mini/results_mini.csv")"
sed -i 's/expect: 125/expect: 124/' "$T/proj/validation/mini.yaml"
expect 1 "20 x 40: fluid mass against 125 kg/m  *FAIL (1)" "$RY" validate mini --root "$T/proj" -o "$T/mini2"

finish

#!/usr/bin/env bash
# A sweep through a real one-node Slurm cluster gives the same table as the same sweep run
# locally, and a point whose result is lost is resubmitted alone.
#
#   tests/sweep/slurm_sweep.sh INIM WORK_DIR
#
# Starts munged, slurmctld and slurmd in a temporary folder (slurm_cluster.sh, which installs
# Debian's slurm-wlm and munge when they are missing), runs a four-point sweep of a small display
# with `inim sweep --jobs 2` and with `inim sweep --slurm --submit` (task 0 alone, then the three
# other array tasks, then the collection step), waits for the jobs and checks:
#   - the four tasks and the collection job completed (scontrol's JobState and ExitCode);
#   - results.csv of the cluster's sweep equals the local one, byte for byte;
#   - after one point's result is removed, --slurm --submit submits one task for that point
#     only, and the collected table is again the same.
# Exit status 77 (skipped, with the reason) where the daemons cannot be started (not root).
set -euo pipefail
INIM="$1"
WORK="$2"
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$WORK"
mkdir -p "$WORK"
CLUSTER=""
cleanup() { [ -z "$CLUSTER" ] || { "$HERE/slurm_cluster.sh" stop "$CLUSTER" >/dev/null 2>&1 || true; rm -rf "$CLUSTER"; }; }
trap cleanup EXIT

# The cluster's folder holds unix sockets: a short path. A start can lose a race for its ports
# with another program: then once more in a fresh folder (its messages stay in the test's log).
for attempt in 1 2 3; do
  CLUSTER="$(mktemp -d /tmp/inim-slurm-XXXXXX)"
  set +e
  started="$("$HERE/slurm_cluster.sh" start "$CLUSTER")"
  status=$?
  set -e
  if [ "$status" -eq 77 ]; then
    echo "$started"
    exit 77
  fi
  [ "$status" -eq 0 ] && break
  echo "slurm_sweep: the cluster did not start (attempt $attempt, status $status): $started"
  cleanup
  CLUSTER=""
  [ "$attempt" -lt 3 ] || exit 1
done
export "$(echo "$started" | tail -n 1)"
echo "slurm_sweep: cluster up, $SLURM_CONF"

cat > "$WORK/display.json" <<'EOF'
{"name": "small sweep test display",
 "panel": {"name": "test panel", "resolution_px": [105, 87], "pixel_pitch_mm": 0.1,
           "primaries": {"R": {"gaussian": {"mean_nm": 625, "fwhm_nm": 35}},
                         "G": {"gaussian": {"mean_nm": 530, "fwhm_nm": 35}},
                         "B": {"gaussian": {"mean_nm": 460, "fwhm_nm": 30}}},
           "peak_luminance_cd_m2": 500},
 "mla": {"name": "test mla", "pitch_mm": 0.9, "focal_length_mm": 3.0, "substrate_thickness_mm": 1.0,
         "material": "PMMA"},
 "generation_gap_mm": 3.0, "reconstruction_gap_mm": 3.5, "ei_px": 9, "ei_count": [11, 9]}
EOF
cat > "$WORK/plan.json" <<'EOF'
{"base": {"display": "display.json",
          "fig11": {"width": 48, "poses": ["centre", "left"], "reference_spp": 2, "eia_spp": 1,
                    "depth_error": false}},
 "axes": [{"path": "reconstruction_gap_mm", "values": [3.2, 3.6]},
          {"path": "mla.focal_length_mm", "values": [2.8, 3.2]}]}
EOF

echo "slurm_sweep: local run"
"$INIM" sweep --plan "$WORK/plan.json" --out "$WORK/local" --jobs 2

echo "slurm_sweep: submitting to the cluster"
submitted="$("$INIM" sweep --plan "$WORK/plan.json" --out "$WORK/cluster" --slurm --submit --cpus-per-task 1 \
             --mem 1G --time-limit 00:10:00)"
echo "$submitted"
# The job ids printed: task 0 alone (it renders the shared references), the other tasks, the collection.
job_ids() { echo "$1" | grep "^submitted:" | grep -o "job [0-9]*" | cut -d' ' -f2; }
mapfile -t jobs < <(job_ids "$submitted")
[ "${#jobs[@]}" -eq 3 ] || { echo "slurm_sweep: expected 3 job ids (first task, array, collection)"; exit 1; }

# Waits until the jobs leave the queue, then checks each record's state (COMPLETED, exit 0:0).
wait_for() {
  local deadline=$((SECONDS + 600)) id
  for id in "$@"; do
    while squeue -h -j "$id" 2>/dev/null | grep -q .; do
      [ "$SECONDS" -lt "$deadline" ] || { echo "slurm_sweep: job $id still queued after 600 s"; squeue; exit 1; }
      sleep 1
    done
  done
  for id in "$@"; do
    local records
    records="$(scontrol -o show job "$id")"
    if echo "$records" | grep -v "JobState=COMPLETED" | grep -q .; then
      echo "slurm_sweep: job $id did not complete:"
      echo "$records" | grep -o "JobId=[0-9]* \|JobState=[A-Z_]*\|ExitCode=[0-9:]*"
      cat "$WORK"/cluster/slurm/logs/* || true
      exit 1
    fi
    echo "$records" | grep -q "ExitCode=0:0" || { echo "slurm_sweep: job $id exit code"; exit 1; }
  done
}
wait_for "${jobs[@]}"
tasks="$( (scontrol -o show job "${jobs[0]}"; scontrol -o show job "${jobs[1]}") | grep -c "JobState=COMPLETED")"
[ "$tasks" -eq 4 ] || { echo "slurm_sweep: $tasks array tasks completed, expected 4"; exit 1; }
cmp "$WORK/local/results.csv" "$WORK/cluster/results.csv"
echo "slurm_sweep: the cluster's table equals the local one ($(wc -l < "$WORK/local/results.csv") lines)"

# One point's result lost: only that point is resubmitted, as one task.
lost="$(ls "$WORK/cluster/points" | sort | head -n 1)"
rm "$WORK/cluster/points/$lost/result.json"
resubmitted="$("$INIM" sweep --out "$WORK/cluster" --slurm --submit --cpus-per-task 1 --mem 1G --time-limit 00:10:00)"
echo "$resubmitted"
echo "$resubmitted" | grep -q "^1 points in 1 array tasks" || { echo "slurm_sweep: resubmission not of one point"; exit 1; }
[ "$(cat "$WORK/cluster/slurm/tasks-2.txt")" = "$lost" ] || { echo "slurm_sweep: tasks-2.txt is not $lost"; exit 1; }
mapfile -t jobs < <(job_ids "$resubmitted")
[ "${#jobs[@]}" -eq 2 ] || { echo "slurm_sweep: expected 2 job ids (array, collection)"; exit 1; }
wait_for "${jobs[@]}"
cmp "$WORK/local/results.csv" "$WORK/cluster/results.csv"
echo "slurm_sweep: the resubmitted point's table equals the local one"

#!/usr/bin/env bash
# Stop what tests/cluster/slurm-up.sh started: exactly the PIDs in $STATE/pids (slurmd, slurmctld,
# slurmdbd, mariadbd, munged, in that order: the reverse of their start), then the link
# /etc/slurm/slurm.conf if slurm-up.sh made it. `--purge` also deletes $STATE (database, logs).
set -euo pipefail
STATE=${CRADLE_SLURM_DIR:-/tmp/cradle-slurm}
[ -s "$STATE/pids" ] || { echo "slurm-down: nothing recorded in $STATE/pids"; exit 0; }
tac "$STATE/pids" | while read -r name pid; do
    if kill -0 "$pid" 2>/dev/null; then
        kill -TERM "$pid"
        for _ in $(seq 80); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
        if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid"; echo "slurm-down: $name ($pid) killed"; else
            echo "slurm-down: $name ($pid) stopped"; fi
    else
        echo "slurm-down: $name ($pid) was not running"
    fi
done
rm -f "$STATE/pids"
if [ -s "$STATE/created" ]; then
    while read -r path; do [ -L "$path" ] && rm -f "$path" && echo "slurm-down: removed $path"; done < "$STATE/created"
    rm -f "$STATE/created"
fi
if [ "${1:-}" = --purge ]; then rm -rf "$STATE"; echo "slurm-down: removed $STATE"; fi

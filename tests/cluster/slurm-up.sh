#!/usr/bin/env bash
# Start a single-node Slurm on this machine from Debian's packages, as plain processes (no systemd):
# munged, mariadbd (job accounting), slurmdbd, slurmctld and slurmd, each in the foreground of its own
# session, every PID recorded in $STATE/pids for slurm-down.sh. Configuration: the templates beside this
# script (slurm.conf.in, slurmdbd.conf.in, my.cnf.in), filled in under $STATE. Run as root.
#
#   tests/cluster/slurm-up.sh            # installs the packages if missing (apt-get), starts, waits until idle
#   export SLURM_CONF=/tmp/cradle-slurm/slurm.conf   # (printed at the end; /etc/slurm/slurm.conf links to it
#                                                    #  when that file did not exist)
#   python -m pytest -m slurm tests/cluster           # the workflow through sbatch against a local build
#   tests/cluster/slurm-down.sh          # stops exactly the processes started here
#
# CRADLE_SLURM_DIR (default /tmp/cradle-slurm): state, logs, database. CRADLE_SLURM_PORT (default 16817):
# slurmctld's port; slurmd, slurmdbd and MariaDB use the next three.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
STATE=${CRADLE_SLURM_DIR:-/tmp/cradle-slurm}
PORT_CTLD=${CRADLE_SLURM_PORT:-16817}
PORT_SLURMD=$((PORT_CTLD + 1)); PORT_DBD=$((PORT_CTLD + 2)); PORT_DB=$((PORT_CTLD + 3))
HOST=$(hostname -s)
CPUS=$(nproc)
MEM=$(awk '/MemTotal/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)   # MB, 10% left to the system

say() { echo "slurm-up: $*"; }
die() { echo "slurm-up: error: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "run as root (the daemons run as root here)"

if [ -s "$STATE/pids" ]; then
    alive=0
    while read -r name pid; do kill -0 "$pid" 2>/dev/null && alive=$((alive + 1)); done < "$STATE/pids"
    [ "$alive" -gt 0 ] && die "$alive processes of an earlier slurm-up are running ($STATE/pids): run slurm-down.sh first"
    rm -f "$STATE/pids"
fi

need=()
for cmd in munged:munge mariadbd:mariadb-server slurmdbd:slurmdbd slurmctld:slurmctld slurmd:slurmd sbatch:slurm-client; do
    command -v "${cmd%%:*}" >/dev/null || need+=("${cmd#*:}")
done
if [ ${#need[@]} -gt 0 ]; then
    say "installing ${need[*]} (apt-get)"
    # policy-rc.d: the packages' own service starts are refused (no systemd here; we start them below)
    printf '#!/bin/sh\nexit 101\n' > /usr/sbin/policy-rc.d && chmod +x /usr/sbin/policy-rc.d
    DEBIAN_FRONTEND=noninteractive apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq munge mariadb-server slurmdbd slurmctld slurmd slurm-client >/dev/null
fi

mkdir -p "$STATE"/{munge,run,log,slurmctld,slurmd,mysql}
chmod 711 "$STATE/munge"           # clients reach the socket; the key inside is 600
fill() {
    sed -e "s|@STATE@|$STATE|g" -e "s|@HOST@|$HOST|g" -e "s|@CPUS@|$CPUS|g" -e "s|@MEM@|$MEM|g" \
        -e "s|@PORT_CTLD@|$PORT_CTLD|g" -e "s|@PORT_SLURMD@|$PORT_SLURMD|g" -e "s|@PORT_DBD@|$PORT_DBD|g" \
        -e "s|@PORT_DB@|$PORT_DB|g" "$HERE/$1.in" > "$STATE/$1"
}
fill slurm.conf; fill slurmdbd.conf; fill my.cnf
chmod 600 "$STATE/slurmdbd.conf"          # slurmdbd refuses a config others can read (it holds a password)
export SLURM_CONF="$STATE/slurm.conf"

start() {   # start NAME CMD...: in its own session, output to log/NAME.out, PID to $STATE/pids
    local name=$1; shift
    setsid "$@" >> "$STATE/log/$name.out" 2>&1 < /dev/null &
    echo "$name $!" >> "$STATE/pids"
}
wait_for() {   # wait_for WHAT SECONDS CMD...
    local what=$1 secs=$2; shift 2
    local end=$((SECONDS + secs))
    while [ "$SECONDS" -lt "$end" ]; do timeout 10 "$@" >/dev/null 2>&1 && return 0; sleep 0.25; done
    die "$what did not come up in ${secs} s (logs: $STATE/log/)"
}

# 1. munge: a key of our own, a socket of our own (AuthInfo=socket=... in both configs)
[ -s "$STATE/munge/munge.key" ] || { dd if=/dev/urandom of="$STATE/munge/munge.key" bs=1024 count=1 status=none;
                                     chmod 600 "$STATE/munge/munge.key"; }
start munged munged --foreground --force --socket="$STATE/munge/munge.socket" --key-file="$STATE/munge/munge.key" \
    --pid-file="$STATE/run/munged.pid" --log-file="$STATE/log/munged.log" --seed-file="$STATE/munge/munged.seed"
wait_for munged 10 test -S "$STATE/munge/munge.socket"

# 2. MariaDB for the accounting (data under $STATE/mysql, loopback only)
if [ ! -d "$STATE/mysql/mysql" ]; then
    mariadb-install-db --defaults-file="$STATE/my.cnf" --auth-root-authentication-method=socket \
        > "$STATE/log/mariadb-install-db.out" 2>&1 || die "mariadb-install-db failed ($STATE/log/mariadb-install-db.out)"
fi
start mariadbd mariadbd --defaults-file="$STATE/my.cnf"
SQL=(mariadb --socket="$STATE/run/mysqld.sock" -uroot)
wait_for mariadbd 60 "${SQL[@]}" -e "select 1"
"${SQL[@]}" -e "CREATE USER IF NOT EXISTS 'slurm'@'127.0.0.1' IDENTIFIED BY 'cradle-test-only';
                CREATE USER IF NOT EXISTS 'slurm'@'localhost' IDENTIFIED BY 'cradle-test-only';
                GRANT ALL ON slurm_acct_db.* TO 'slurm'@'127.0.0.1'; GRANT ALL ON slurm_acct_db.* TO 'slurm'@'localhost';"

# 3. slurmdbd, then the cluster, an account and this user in the accounting (sbatch/sacct need them)
start slurmdbd slurmdbd -D          # reads slurmdbd.conf beside $SLURM_CONF
wait_for slurmdbd 60 sacctmgr -n list cluster
sacctmgr -i -Q add cluster cradle >/dev/null 2>&1 || true
sacctmgr -i -Q add account cradle Description=cradle Organization=cradle >/dev/null 2>&1 || true
sacctmgr -i -Q add user "$(id -un)" Account=cradle >/dev/null 2>&1 || true

# 4. slurmctld and slurmd, until the node is idle
start slurmctld slurmctld -D -f "$STATE/slurm.conf"
wait_for slurmctld 60 scontrol ping
start slurmd slurmd -D -f "$STATE/slurm.conf"
for _ in $(seq 240); do
    state=$(sinfo -h -N -o %T 2>/dev/null | head -1)
    [ "$state" = idle ] && break
    sleep 0.25
done
[ "$state" = idle ] || die "node state '$state', not idle, after 60 s (logs: $STATE/log/)"

# /etc/slurm/slurm.conf: the default path of every Slurm command (and of the Snakemake plugin's calls)
if [ ! -e /etc/slurm/slurm.conf ]; then
    mkdir -p /etc/slurm && ln -s "$STATE/slurm.conf" /etc/slurm/slurm.conf && echo /etc/slurm/slurm.conf > "$STATE/created"
fi
say "up: node $HOST, $CPUS CPUs, $MEM MB, partition local; processes in $STATE/pids"
say "export SLURM_CONF=$STATE/slurm.conf"

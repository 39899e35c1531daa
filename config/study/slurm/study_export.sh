#!/bin/bash
# Re-exports a whole study on a Slurm cluster: one array task per shard of the manifest, then one
# job that merges the shards' parts (docs/study-on-slurm.md). The same script is the submitter
# and both jobs' body.
#
#   study_export.sh submit N MANIFEST OUT [study export options, e.g. --volumes --size 1920x1080]
#     submits `--array=1-N` shard jobs and a merge job that starts when all of them have ended;
#     prints both job ids ("array JOBID", "merge JOBID"). Extra sbatch options go in
#     CB_SBATCH_OPTIONS (e.g. "--partition=short --time=02:00:00"); the cloudbrush binary is
#     $CLOUDBRUSH (default: cloudbrush on PATH, resolved when submitting).
#   (the jobs run it as) study_export.sh shard|merge MANIFEST OUT [options]
#
# OUT must be on a file system every node sees. A shard exits 3 when one of its journals is
# damaged (its parts hold every whole record around the damage); the merge still runs (it waits
# for the array with afterany) and exits 3 too, naming them. A shard that failed leaves no
# shard.txt, and the merge refuses to join an incomplete set, naming the missing shard.
set -euo pipefail

mode=${1:-}
case "$mode" in
  submit)
    [ $# -ge 4 ] || { echo "usage: $0 submit N MANIFEST OUT [export options]" >&2; exit 2; }
    count=$2 manifest=$(readlink -f "$3") out=$(readlink -f "$4")
    shift 4
    [[ "$count" =~ ^[1-9][0-9]*$ ]] || { echo "$0: N must be a whole number >= 1, got '$count'" >&2; exit 2; }
    [ -f "$manifest" ] || { echo "$0: $manifest: no such manifest" >&2; exit 2; }
    cloudbrush=$(command -v "${CLOUDBRUSH:-cloudbrush}") ||
      { echo "$0: ${CLOUDBRUSH:-cloudbrush}: not found (set CLOUDBRUSH)" >&2; exit 2; }
    self=$(readlink -f "$0")
    mkdir -p "$out/slurm-logs"
    # shellcheck disable=SC2086  # CB_SBATCH_OPTIONS is a list of options
    array=$(sbatch --parsable ${CB_SBATCH_OPTIONS:-} --job-name=cb-export --array="1-$count" \
      --output="$out/slurm-logs/shard-%a.log" --export=ALL,CLOUDBRUSH="$cloudbrush" \
      "$self" shard "$manifest" "$out" "$@")
    array=${array%%;*}
    # shellcheck disable=SC2086
    merge=$(sbatch --parsable ${CB_SBATCH_OPTIONS:-} --job-name=cb-export-merge \
      --dependency="afterany:$array" --output="$out/slurm-logs/merge.log" \
      --export=ALL,CLOUDBRUSH="$cloudbrush" "$self" merge "$manifest" "$out" "$@")
    echo "array ${array}"
    echo "merge ${merge%%;*}"
    ;;
  shard)
    manifest=$2 out=$3
    shift 3
    : "${SLURM_ARRAY_TASK_ID:?a shard runs as a task of the job array (use: $0 submit ...)}"
    exec "${CLOUDBRUSH:-cloudbrush}" study export --manifest "$manifest" --out "$out" \
      --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" "$@"
    ;;
  merge)
    manifest=$2 out=$3
    shift 3
    # The merge writes only the trace files and the codebook; --volumes, --size and such were
    # the shards' business.
    keep=()
    while [ $# -gt 0 ]; do
      case "$1" in
        --protocol) keep+=("$1" "$2"); shift 2 ;;
        --size) shift 2 ;;
        *) shift ;;
      esac
    done
    exec "${CLOUDBRUSH:-cloudbrush}" study export --manifest "$manifest" --out "$out" --merge \
      "${keep[@]}"
    ;;
  *)
    echo "usage: $0 submit N MANIFEST OUT [study export options]" >&2
    exit 2
    ;;
esac

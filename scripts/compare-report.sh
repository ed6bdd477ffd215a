# Sourced by the table scripts that read `stex compare` reports over the shared photos
# (structure-table.sh, blend-contrast-table.sh): the photos' folder, a work folder removed on
# exit, and the report's fields. Needs $root (the repository).
exemplars="$root/../shared/exemplars"
[ -d "$exemplars" ] || { echo "$(basename "$0"): $exemplars is missing (the shared photos)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The first number after the last ": " of the line starting with $1 ("structure distance").
after() { awk -v l="$1" 'index($0, l) == 1 { sub(/.*: /, ""); print $1 }'; }
# A structure-distance part by name ("cross-scale").
part() { awk -v p="$1" '/^  marginals / { for (i = 1; i < NF; ++i) if ($i == p) print $(i + 1) }'; }

# Sourced by the scripts and benches that loop over models, so that a model registered in the
# core enters them without a second list to keep by hand.
#   registry_models STEX [CAPABILITY…]   the registry's model names (`stex models --json`), in its
#                                        order, one a line: those with every capability named
#                                        (analysis, solid, morph, pov_procedural, osl,
#                                        light_direction, gaussian_channels, joint_colour).
# Models that only tests register (test_*) are never listed: they are not the product's.
registry_models() {
    local stex="${1:?registry_models: STEX [CAPABILITY...]}"
    shift
    "$stex" models --json | python3 -c '
import json, sys
wanted = sys.argv[1:]
for model in json.load(sys.stdin)["models"]:
    unknown = [c for c in wanted if c not in model["capabilities"]]
    if unknown:
        sys.exit("registry_models: no capability " + ", ".join(unknown))
    if not model["name"].startswith("test_") and all(model["capabilities"][c] for c in wanted):
        print(model["name"])' "$@"
}

# Sourced by the bench scripts: the uniform --size of each ../shared benchmark structure that
# gives GSSE about 1e5 and about 6e5 tetrahedra (docs/benchmarks.md), and H, the first of them.
declare -A SIZES=([mosfet]="0.0304 0.0161" [diffusion]="0.0451 0.0248" [trench]="0.0442 0.0243" [finfet]="0.0276 0.0152")
declare -A H=()
for _s in "${!SIZES[@]}"; do H[$_s]=${SIZES[$_s]%% *}; done
unset _s

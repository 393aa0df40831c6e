#!/usr/bin/env bash
# The paper's two examples, each in three variants side by side:
#   paper   - collocation operator + element exclusion (the scene as shipped)
#   exact   - Galerkin operator + active set (exact discrete contact)
#   bonded  - Galerkin operator, bonded contact (the soil also pulls)
# then the figures (the paper's Figures 4-7 and a contact map) by gnuplot.
# usage: bash scripts/paper_examples.sh [build/plate-on-halfspace]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
for example in example1 example2; do
  for variant in paper exact bonded; do
    directory=output/$example/$variant
    case $variant in
      paper) extra="" ;;
      exact) extra=$'subsection Discretization\n set Flexibility = galerkin\nend\nsubsection Contact\n set Method = active set\nend' ;;
      bonded) extra=$'subsection Discretization\n set Flexibility = galerkin\nend\nsubsection Foundation\n set Contact = bonded\nend' ;;
    esac
    mkdir -p "$directory"
    printf 'include %s\nset Output directory = %s\n%s\n' \
      "parameters/$example.prm" "$directory" "$extra" >"$directory/scene.prm"
    echo "== $example, $variant"
    "$program" "$directory/scene.prm" | grep -E "contact iteration|area|violation|check" | tail -4
  done
  gnuplot -e "example='$example'" scripts/paper_figures.gp
  python3 scripts/compare_variants.py "output/$example"
done
echo "figures: output/example1/*.png output/example2/*.png"

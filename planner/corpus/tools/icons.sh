#!/usr/bin/env bash
# Copies the corpus' icons, byte for byte, from the npm packages installed in the current
# folder:
#   npm install bootstrap-icons@1.13.2 @mdi/svg@7.4.47 ionicons@8.1.0 @fortawesome/fontawesome-free@7.3.1
#   bash icons.sh OUTDIR
set -euo pipefail
out=${1:?usage: icons.sh OUTDIR}
mkdir -p "$out"
nm=node_modules
for n in cat dog horse fish dove frog hippo kiwi-bird crow key puzzle-piece gear paw; do
  cp "$nm/@fortawesome/fontawesome-free/svgs/solid/$n.svg" "$out/fa-$n.svg"
done
for n in heart-fill star-fill apple trophy-fill tree-fill; do
  cp "$nm/bootstrap-icons/icons/$n.svg" "$out/bi-$n.svg"
done
for n in rabbit duck owl cat dog; do
  cp "$nm/@mdi/svg/svg/$n.svg" "$out/mdi-$n.svg"
done
for n in heart-outline leaf; do
  cp "$nm/ionicons/dist/svg/$n.svg" "$out/ion-$n.svg"
done

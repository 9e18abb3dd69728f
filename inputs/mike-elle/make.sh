#!/bin/sh
# Writes the data files and decks of this folder (bonded_lattice.scenes) and runs each
# small deck once on 1 rank, keeping its log.  Run from this folder: sh make.sh
set -e
DATE=${DATE:-$(date +%d%b%y)}
scene() {   # folder, kind, options...
    out=$1; kind=$2; shift 2
    bonded-lattice scene "$kind" --n 30 --out "$out" "$@" > /dev/null
    bonded-lattice scene "$kind" --n 30 --out "$out" --mode dynamic --crossings 80 "$@" > /dev/null
}
scene layer-extension layer-extension --steps 24 --strain-step 5e-6
scene layer-compression layer-compression --steps 40 --strain-step 1e-5
scene polycrystal polycrystal --grains 12 --steps 40 --strain-step 5e-6
scene expanding expanding --grains 12 --expanding 2 --steps 20 --strain-step 5e-5
for d in layer-extension layer-compression polycrystal expanding; do
    for m in quasistatic dynamic; do
        (cd $d && if [ $m = quasistatic ]; then rm -f breaks.txt; fi && lmp -in in.$d.$m -log log.$DATE.$d-$m.g++.1 -screen none \
            && mv scene.dat scene.$m.dat)
    done
done
# the polycrystal in a periodic box (no walls), relaxed by lattice/quasistatic relax local
bonded-lattice scene polycrystal --n 30 --grains 12 --steps 40 --strain-step 5e-6 \
    --boundary periodic --relax local --out polycrystal-periodic-local > /dev/null
(cd polycrystal-periodic-local && rm -f breaks.txt && lmp -in in.polycrystal.quasistatic \
    -log log.$DATE.polycrystal-periodic-local.g++.1 -screen none && mv scene.dat scene.quasistatic.dat)

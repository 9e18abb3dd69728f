/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The query API of pair_style lattice/bond for other styles (computes
   lattice/bonds, lattice/bond/local and lattice/energy, fix lattice/energy,
   lattice/quasistatic, the bond files): each record's parameters, load and
   spring, the elastic energy, and the breaking of a record by hand.  The
   physics of a record is that of the force loop (lattice_bond_physics.h).
------------------------------------------------------------------------- */

#include "pair_lattice_bond.h"

#include "atom.h"
#include "domain.h"
#include "fix_lattice_bond_store.h"
#include "lattice_bond_physics.h"
#include "lattice_bond_records.h"
#include "lattice_heterogeneity.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace LAMMPS_NS::LatticeBondPhysics;

/* ---------------------------------------------------------------------- */

const int *PairLatticeBond::partner_index() const
{
  return records->partner_index();
}

int PairLatticeBond::partner_index_stride() const
{
  return records->stride();
}

/* ----------------------------------------------------------------------
   a bond's parameters: the type pair's, scaled by the bond's stiffness and
   strength factors in heterogeneous rock (scaled_params)
------------------------------------------------------------------------- */

PairLatticeBond::BondParams PairLatticeBond::bond_params(int i, int j) const
{
  const BondParams &p = params[atom->type[i]][atom->type[j]];
  if (!hetero->enabled()) return p;
  return hetero->bond_params(p, i, j);
}

/* ----------------------------------------------------------------------
   how close intact record s of local atom i is to breaking at the current
   positions and springs (as the last force evaluation left them): the larger
   of the tensile ratio Fn / (Kn Xb) = Xn / Xb and the shear ratio
   (Fs + mu_p Fn) / Fs0 (the Coulomb limit Fs <= Fs0 - mu_p Fn as a ratio;
   tensile_ratio and shear_ratio in lattice_bond_physics.h).  A bond breaks
   when it exceeds 1.  mode: BreakMode::Tension or BreakMode::Shear, the
   larger one; ratio 0 and BreakMode::None for other records
------------------------------------------------------------------------- */

PairLatticeBond::BondLoad PairLatticeBond::bond_load(int i, int s, BreakMode &mode) const
{
  mode = BreakMode::None;
  const int *partner_idx = records->partner_index();
  const int j = partner_idx ? partner_idx[(bigint) i * records->stride() + s] : -1;
  BondLoad load{bond_params(i, j >= 0 ? j : i), 0.0, 0.0, 0.0, 0.0};
  if (j < 0) return load;    // a broken bond whose particles are far apart
  load.dist = pair_separation(atom->x, i, j).length();
  const double xn = normal_stretch(load.dist, radii().touch(i, j));
  const bool intact = (fix_store->states(i)[s] == LB_INTACT);
  if (!intact && contact_open(xn)) return load;    // an open contact carries no force
  const BondParams &p = load.p;
  load.fn = normal_force(p.kn, xn);
  load.fs = shear_force(p.ks, fix_store->spring_squared(i, s));
  if (!intact) return load;
  const double tension = tensile_ratio(xn, p.xb);
  const double shear = shear_ratio(load.fs, p.mu_p, load.fn, p.fs0);
  mode = (tension >= shear) ? BreakMode::Tension : BreakMode::Shear;
  load.ratio = MAX(tension, shear);
  return load;
}

/* ---------------------------------------------------------------------- */

bool PairLatticeBond::has_shear_springs() const
{
  if (!allocated) return false;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (coeff_set[i][j] && params[i][j].ks > 0.0) return true;
  return false;
}

/* ----------------------------------------------------------------------
   break intact record s of local atom i in the given mode (lattice/quasistatic);
   the next force evaluation lets its springs go as the force loop does
------------------------------------------------------------------------- */

void PairLatticeBond::break_record(int i, int s, BreakMode mode)
{
  LatticeBondState &st = fix_store->states(i)[s];
  if (st == LB_INTACT && mode != BreakMode::None) st = broken_state(mode);
}

/* ----------------------------------------------------------------------
   the shear spring of record s of local atom i as a vector (force on the
   owner -Ks times it): 2D springs are stored as signed lengths along
   t = z x n.  False if the partner of a loaded 2D spring is not on this
   rank (its direction is then unknown)
------------------------------------------------------------------------- */

bool PairLatticeBond::shear_vector(int i, int s, double *out) const
{
  const int nc = fix_store->spring_components();
  const double *sh = fix_store->springs(i) + s * nc;
  for (int k = 0; k < 3; k++) out[k] = (k < nc) ? sh[k] : 0.0;
  if (fix_store->shear_layout() != FixLatticeBondStore::SHEAR_PLANAR || sh[0] == 0.0) return true;
  const tagint partner = fix_store->partners(i)[s];
  int j = atom->map(partner);
  if (j >= 0) j = domain->closest_image(i, j);
  if (j < 0 || atom->tag[j] != partner) return false;
  const PairSeparation d = pair_separation(atom->x, i, j);
  const double rinv = 1.0 / sqrt(d.dx * d.dx + d.dy * d.dy);    // 2D: in the plane
  out[0] = -sh[0] * d.dy * rinv;
  out[1] = sh[0] * d.dx * rinv;
  out[2] = 0.0;
  return true;
}

/* ----------------------------------------------------------------------
   elastic energy of the records owned by this rank at the current positions
   (the springs as the last force evaluation left them)
------------------------------------------------------------------------- */

double PairLatticeBond::local_elastic_energy() const
{
  const int *partner_idx = records->partner_index();
  if (!fix_store || !partner_idx) return 0.0;
  double **x = atom->x;
  const Radii radius = radii();
  const int stride = records->stride();
  double energy = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const LatticeBondState *st = fix_store->states(i);
    const int *idx = partner_idx + (bigint) i * stride;
    for (int s = 0; s < fix_store->record_count(i); s++) {
      const int j = idx[s];
      if (j < 0) continue;
      const double xn = normal_stretch(pair_separation(x, i, j).length(), radius.touch(i, j));
      if (st[s] != LB_INTACT && contact_open(xn)) continue;
      const BondParams p = bond_params(i, j);
      energy += record_energy(p.kn, xn, p.ks, fix_store->spring_squared(i, s));
    }
  }
  return energy;
}

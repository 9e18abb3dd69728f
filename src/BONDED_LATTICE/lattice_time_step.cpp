/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The time step of pair_style lattice/bond: see lattice_time_step.h
------------------------------------------------------------------------- */

#include "lattice_time_step.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "lattice_errors.h"
#include "pair_lattice_bond.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

// a warning above this fraction of the critical time step (see check)
static constexpr double DT_SAFETY_FRACTION = 0.5;
// a particle moving more than this fraction of the smallest radius in one step
// means the integration has become unstable
static constexpr double STEP_LIMIT_FRACTION = 0.1;

/* ---------------------------------------------------------------------- */

double LatticeTimeStep::step_limit(double min_radius)
{
  return STEP_LIMIT_FRACTION * min_radius;
}

/* ----------------------------------------------------------------------
   critical time step of the bonded lattice, reported at the start of each
   run: velocity Verlet is stable for dt < 2 / omega_max, and by Gershgorin's
   theorem omega_max^2 <= max_i 2 sum_j k_ij / m_i over the particle's records
   (k = max(Kn, Ks): each bond's stiffness matrix has eigenvalues Kn and Ks),
   so dt_c = 2 / sqrt(max_i 2 sum_j k_ij / m_i).  It is a lower bound of the
   exact limit (0.6-0.9 of it for regular lattices: docs/theory.md,
   "Critical time step"; conversion.critical_time_step); walls and damping
   are not included.
   In LAMMPS units a force f on a mass m accelerates it by ftm2v f / m
   (fix nve's arithmetic), so k / m is a squared frequency only times ftm2v
   (1 in si, cgs, micro, nano, lj; 1 / 1.0364269e-4 in metal)
------------------------------------------------------------------------- */

void LatticeTimeStep::check(const PairLatticeBond &pair, LatticeCommCarrier &carrier)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double *rmass = atom->rmass;    // per-atom masses, or per-type ones (atom->mass)
  const double *mass = atom->mass;
  const int *type = atom->type;
  const FixLatticeBondStore *store = pair.store();
  const int *partner_idx = pair.partner_index();
  const int stride = pair.partner_index_stride();
  stiffness_sum.assign(nall, 0.0);
  for (int i = 0; i < nlocal; i++) {
    const int *idx = partner_idx + (bigint) i * stride;
    for (int s = 0; s < store->record_count(i); s++) {
      const int j = idx[s];
      if (j < 0) continue;
      const LatticeBondParams p = pair.bond_params(i, j);
      const double k = MAX(p.kn, p.ks);
      stiffness_sum[i] += k;
      stiffness_sum[j] += k;
    }
  }
  carrier.carry_reverse(this);
  double lambda_local = 0.0, lambda = 0.0;
  for (int i = 0; i < nlocal; i++) {
    const double m = rmass ? rmass[i] : mass[type[i]];
    if (m > 0.0) lambda_local = MAX(lambda_local, 2.0 * stiffness_sum[i] / m);
  }
  MPI_Allreduce(&lambda_local, &lambda, 1, MPI_DOUBLE, MPI_MAX, world);
  lambda *= force->ftm2v;    // omega^2 in 1/time^2 (x 1.0 in si: the same bits)
  dt_critical = (lambda > 0.0) ? 2.0 / sqrt(lambda) : 0.0;
  if (dt_critical <= 0.0) return;
  const double dt = update->dt;
  if (comm->me == 0)
    utils::logmesg(lmp, "pair_style lattice/bond: critical time step {:.6g} (stiffest particle, "
                   "walls not included); the time step {:.6g} is {:.3f} of it\n", dt_critical, dt,
                   dt / dt_critical);
  if (dt > DT_SAFETY_FRACTION * dt_critical && comm->me == 0)
    error->warning(FLERR, "Time step {:.6g} is {:.2f} of the critical time step {:.6g} of "
                   "pair_style lattice/bond (above the safety fraction {}): the run may become "
                   "unstable; use a time step of at most {:.6g}", dt, dt / dt_critical, dt_critical,
                   DT_SAFETY_FRACTION, DT_SAFETY_FRACTION * dt_critical);
}

/* ---------------------------------------------------------------------- */

std::string LatticeTimeStep::instability_message(const FixLatticeBondStore *store, int i,
                                                 double min_radius) const
{
  double **x = atom->x;
  const double *d = store->displacements() + 3 * i;
  const double step = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double dt = update->dt;
  return fmt::format(
      "pair_style lattice/bond: atom {} moved {:.6g} in one time step at step {} (more than a "
      "tenth of the smallest particle radius, {:.6g}; it is now at {:.6g} {:.6g} {:.6g}): the "
      "integration is unstable. The time step {:.6g} is {:.2f} of the critical time step {:.6g} "
      "reported at the start of the run: reduce it to at most {:.6g}, or look for a much stiffer "
      "wall or type pair",
      atom->tag[i], step, update->ntimestep, step_limit(min_radius), x[i][0], x[i][1], x[i][2], dt,
      dt_critical > 0.0 ? dt / dt_critical : 0.0, dt_critical, DT_SAFETY_FRACTION * dt_critical);
}

/* ----------------------------------------------------------------------
   only the rank that owns atom i knows (the force loop has no collective):
   error->one, with the wait that lets its message reach the user
   (lattice_errors.h)
------------------------------------------------------------------------- */

void LatticeTimeStep::report_instability(const FixLatticeBondStore *store, int i,
                                         double min_radius) const
{
  lattice_error_one(lmp, FLERR, instability_message(store, i, min_radius));
}

/* ----------------------------------------------------------------------
   every rank is here: error->all with the message of the lowest rank that
   has a runaway atom (printed by rank 0, to the screen and the log file)
------------------------------------------------------------------------- */

void LatticeTimeStep::stop_if_unstable(FixLatticeBondStore *store, double min_radius) const
{
  const int runaway = store->update_displacements(step_limit(min_radius));
  lattice_error_from_any_rank(lmp, FLERR, runaway >= 0,
                              runaway >= 0 ? instability_message(store, runaway, min_radius)
                                           : std::string());
}

/* ----------------------------------------------------------------------
   reverse communication: ghosts' stiffness sums to their owners
------------------------------------------------------------------------- */

int LatticeTimeStep::pack_reverse(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) buf[k] = stiffness_sum[first + k];
  return n;
}

/* ---------------------------------------------------------------------- */

void LatticeTimeStep::unpack_reverse(int n, const int *list, const double *buf)
{
  for (int k = 0; k < n; k++) stiffness_sum[list[k]] += buf[k];
}

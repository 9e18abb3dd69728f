/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   fix lattice/wall: a flat wall perpendicular to one axis.  A particle of
   radius R whose centre lies a distance h inside the wall overlaps it by
   delta = R - h; the wall pushes it inward with Kn*delta and resists
   sliding with a shear spring Ks capped at mu*Kn*delta (Li et al. 2018,
   particle-wall contact).  Optionally the wall moves at constant speed,
   follows an equal-style variable (e.g. the papers' stepwise loading) or
   holds a normal stress (servo).
------------------------------------------------------------------------- */

#include "fix_lattice_wall.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "lattice_bond_physics.h"
#include "pair_lattice_bond.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace LatticeBondPhysics;

/* ---------------------------------------------------------------------- */

FixLatticeWall::FixLatticeWall(LAMMPS *lmp, int narg, char **arg) :
    FixLatticeAtomHistory(lmp, narg, arg), pos_var(-1), vel(0.0), servo(0), servo_force(0.0), servo_gain(0.5),
    uniform_radius(0.0), history_ready(0),
    wall_energy(0.0), force_flag(0), tally_flag(0), work(0.0), heat(0.0), fnormal_prev(0.0),
    wall_prev(0.0)
{
  if (narg < 8)
    error->all(FLERR, "Illegal fix lattice/wall command: expected fix ID group lattice/wall "
               "face position Kn Ks mu [vel v | servo P A [gain g]]");

  const std::string face = arg[3];
  if (face == "xlo" || face == "xhi") dim = 0;
  else if (face == "ylo" || face == "yhi") dim = 1;
  else if (face == "zlo" || face == "zhi") dim = 2;
  else error->all(FLERR, "fix lattice/wall face {} is not valid: use xlo xhi ylo yhi zlo zhi", face);
  if (dim == 2 && domain->dimension == 2)
    error->all(FLERR, "fix lattice/wall face {} is not allowed in a 2d simulation", face);
  inward = utils::strmatch(face, "lo$") ? 1 : -1;

  // a v_name position follows an equal-style variable, re-evaluated every step
  if (utils::strmatch(arg[4], "^v_")) {
    pos_var_name = arg[4] + 2;
    pos0 = 0.0;
  } else {
    pos0 = utils::numeric(FLERR, arg[4], false, lmp);
  }
  kn = utils::numeric(FLERR, arg[5], false, lmp);
  ks = utils::numeric(FLERR, arg[6], false, lmp);
  mu = utils::numeric(FLERR, arg[7], false, lmp);
  if (!(kn > 0.0)) error->all(FLERR, "fix lattice/wall Kn = {} is out of range: need Kn > 0", kn);
  if (!(ks >= 0.0)) error->all(FLERR, "fix lattice/wall Ks = {} is out of range: need Ks >= 0", ks);
  if (!(mu >= 0.0)) error->all(FLERR, "fix lattice/wall mu = {} is out of range: need mu >= 0", mu);

  int iarg = 8;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "vel") {
      if (iarg + 1 >= narg) error->all(FLERR, "fix lattice/wall keyword vel needs a value");
      vel = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (key == "servo") {
      if (iarg + 2 >= narg)
        error->all(FLERR, "fix lattice/wall keyword servo needs two values: stress P and area A");
      const double stress = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      const double area = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(stress >= 0.0))
        error->all(FLERR, "fix lattice/wall servo stress {} is out of range: need P >= 0 "
                   "(compression positive)", stress);
      if (!(area > 0.0))
        error->all(FLERR, "fix lattice/wall servo area {} is out of range: need A > 0", area);
      servo = 1;
      // pressure x area is a force only after LAMMPS' pressure factor (P = energy /
      // volume x nktv2p: bar in metal, atm in real; 1 in si, cgs, micro, nano, lj)
      servo_force = stress * area / force->nktv2p;
      iarg += 3;
    } else if (key == "gain") {
      if (iarg + 1 >= narg) error->all(FLERR, "fix lattice/wall keyword gain needs a value");
      servo_gain = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(servo_gain > 0.0 && servo_gain <= 1.0))
        error->all(FLERR, "fix lattice/wall gain {} is out of range: need 0 < gain <= 1",
                   servo_gain);
      iarg += 2;
    } else {
      error->all(FLERR, "Unknown fix lattice/wall keyword {}: valid are vel, servo, gain", key);
    }
  }
  if (servo && vel != 0.0)
    error->all(FLERR, "fix lattice/wall: vel and servo exclude each other (a servo wall sets "
               "its own speed)");
  if (!pos_var_name.empty() && (servo || vel != 0.0))
    error->all(FLERR, "fix lattice/wall: a variable position v_{} excludes vel and servo (the "
               "variable alone sets where the wall is)", pos_var_name);
  if (!pos_var_name.empty()) find_position_variable();

  t0 = current_time();

  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 5;
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[5]{1, 1, 1, 0, 1};
  energy_global_flag = 1;
  restart_global = 1;
  dynamic_group_allow = 1;
  create_history(6);
  std::memset(wall_force, 0, sizeof(wall_force));
}

/* ---------------------------------------------------------------------- */

FixLatticeWall::~FixLatticeWall()
{
  delete[] extlist;
}

/* ---------------------------------------------------------------------- */

int FixLatticeWall::setmask()
{
  return POST_FORCE | MIN_POST_FORCE;
}

/* ---------------------------------------------------------------------- */

double FixLatticeWall::current_time() const
{
  return update->atime + (double) (update->ntimestep - update->atimestep) * update->dt;
}

/* ---------------------------------------------------------------------- */

double FixLatticeWall::position() const
{
  if (pos_var >= 0) return input->variable->compute_equal(pos_var);
  return pos0 + vel * (current_time() - t0);
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::find_position_variable()
{
  pos_var = input->variable->find(pos_var_name.c_str());
  if (pos_var < 0)
    error->all(FLERR, "fix lattice/wall position variable {} does not exist: define it with "
               "variable {} equal ... before the fix", pos_var_name, pos_var_name);
  if (!input->variable->equalstyle(pos_var))
    error->all(FLERR, "fix lattice/wall position variable {} is not equal-style: the wall "
               "needs one number per step", pos_var_name);
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::init()
{
  // variables may have been redefined since the fix was created
  if (!pos_var_name.empty()) find_position_variable();
  // without per-atom radii (e.g. atom_style atomic) every particle has the
  // diameter of pair_style lattice/bond (keyword diameter)
  uniform_radius = 0.0;
  if (!atom->radius_flag) {
    auto *pair = PairLatticeBond::find(force);
    if (!pair || !(pair->uniform_diameter() > 0.0))
      error->all(FLERR, "fix lattice/wall needs the particles' radii: per-atom radii (atom_style "
                 "sphere), or pair_style lattice/bond with the keyword diameter for atom_style {}",
                 atom->get_style());
    uniform_radius = 0.5 * pair->uniform_diameter();
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::setup(int /*vflag*/)
{
  if (!history_ready) {
    for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
    history_ready = 1;
  }
  // the forces of the step already taken: a servo wall does not move here,
  // so a run split in pieces follows the uninterrupted one
  apply_forces(false);
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::min_setup(int vflag)
{
  setup(vflag);
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::min_post_force(int vflag)
{
  post_force(vflag);
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::post_force(int /*vflag*/)
{
  apply_forces(true);
}

/* ----------------------------------------------------------------------
   wall forces at the current wall position; a servo wall then moves for
   the next step by gain * (force error) / (Kn * contacts), the usual DEM
   servo (a full correction of a stiffness Kn per touching particle).
   With tallies on, a step taken adds the wall's work on the particles,
   trapezoidal in this rank's old and new normal force (a sum over atoms, so
   atoms changing rank do not matter), and the heat of the shear springs as
   in pair lattice/bond: Ks/2 [(s1 + s2).ds - |s2|^2 + |s1|^2].
   The contact's physics is pair lattice/bond's (lattice_bond_physics.h):
   the Coulomb cap, the heat and the energy; the spring's tangent plane is
   the wall's and does not turn, so the spring's update (spring_step) is the
   tangential increment added to it.
------------------------------------------------------------------------- */

void FixLatticeWall::apply_forces(bool step_taken)
{
  double **x = atom->x;
  double **f = atom->f;
  const double *radius = atom->radius_flag ? atom->radius : nullptr;    // or uniform_radius
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double wall = position();

  force_flag = 0;
  std::memset(wall_force, 0, sizeof(wall_force));
  wall_energy = 0.0;
  const bool tally = tally_flag && step_taken;
  double q = 0.0;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;

    // tangential displacement since the last step (periodic jumps removed)
    double *s = history(i);     // shear spring
    double *xprev = s + 3;        // position at the last step
    double inc[3] = {x[i][0] - xprev[0], x[i][1] - xprev[1], x[i][2] - xprev[2]};
    unwrap_step(inc);
    inc[dim] = 0.0;
    xprev[0] = x[i][0];
    xprev[1] = x[i][1];
    xprev[2] = x[i][2];

    const double h = inward * (x[i][dim] - wall);    // centre's distance inside the wall
    const double delta = (radius ? radius[i] : uniform_radius) - h;
    if (delta <= 0.0) {
      if (tally && ks > 0.0)   // a spring left behind by a lost contact lets go
        q += wall_release(ks, s, inc);
      s[0] = s[1] = s[2] = 0.0;
      continue;
    }

    const double fn = normal_force(kn, delta);    // compression positive: -Fn of the pair
    double fs[3] = {0.0, 0.0, 0.0};
    double es = 0.0;
    if (ks > 0.0) {
      const double s1[3] = {s[0], s[1], s[2]};
      for (int k = 0; k < 3; k++) s[k] += inc[k];
      s[dim] = 0.0;
      const double s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
      // Coulomb sliding, Ks |S| <= mu Fn: the pair's limit -mu Fn with its Fn = -fn
      // (negating both factors gives the same bits)
      const double limit = friction_limit(mu, -fn);
      if (slides(shear_force_squared(ks, s2), limit)) {
        const double scale = slide_scale(ks, limit, s2);
        for (int k = 0; k < 3; k++) s[k] *= scale;
        if (tally) wall_slide_heat(ks, s1, inc, s, q);
      }
      for (int k = 0; k < 3; k++) fs[k] = -ks * s[k];
      es = spring_energy(ks, s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    }
    fs[dim] = inward * fn;
    for (int k = 0; k < 3; k++) {
      f[i][k] += fs[k];
      wall_force[k] -= fs[k];
    }
    wall_force[3] += 1.0;
    wall_energy += normal_energy(kn, delta) + es;
  }

  if (tally) {
    const double fnormal = -wall_force[dim];    // this rank's force on the particles
    work += 0.5 * (fnormal_prev + fnormal) * (wall - wall_prev);
    heat += q;
  }
  fnormal_prev = -wall_force[dim];
  wall_prev = wall;

  if (servo && step_taken) {
    compute_scalar();    // global force and contacts of this step
    const double pushed = -inward * total[dim];    // compression positive
    const double contacts = MAX(1.0, total[3]);
    pos0 -= inward * servo_gain * (pushed - servo_force) / (kn * contacts);
  }
}

/* ---------------------------------------------------------------------- */

double FixLatticeWall::compute_scalar()
{
  if (!force_flag) {
    double local[5] = {wall_force[0], wall_force[1], wall_force[2], wall_force[3], wall_energy};
    MPI_Allreduce(local, total, 5, MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
  }
  return total[4];
}

/* ----------------------------------------------------------------------
   1-3: force exerted by the particles on the wall, 4: wall position,
   5: number of particles touching it
------------------------------------------------------------------------- */

double FixLatticeWall::compute_vector(int n)
{
  if (n == 3) return position();
  compute_scalar();
  return n < 3 ? total[n] : total[3];
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::set_arrays(int i)
{
  for (int k = 0; k < 3; k++) {
    history(i)[k] = 0.0;              // shear spring
    history(i)[3 + k] = atom->x[i][k];    // position
  }
}

/* ----------------------------------------------------------------------
   global restart: the wall's position, so a moving platen continues from it
------------------------------------------------------------------------- */

void FixLatticeWall::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    // where the wall is now; a restarted run may give a new vel
    double list[2] = {position(), current_time()};
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 2, fp);
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeWall::restart(char *buf)
{
  auto list = (double *) buf;
  pos0 = list[0];
  t0 = list[1];
  history_ready = 1;
}


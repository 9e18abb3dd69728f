/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The life of the records of pair_style lattice/bond: see
   lattice_bond_records.h
------------------------------------------------------------------------- */

#include "lattice_bond_records.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "lattice_errors.h"
#include "lattice_heterogeneity.h"
#include "lattice_time_step.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

// at bonding (and for unbonded pairs at each reneighbouring) two atoms closer
// than this fraction of r_i + r_j are at the same position: coincident atoms
static constexpr double COINCIDENT_FRACTION = 1.0e-6;
// the deepest overlap a bondable pair may have at bonding, relative to r_i + r_j,
// when the bonding tolerance is smaller (tolerance 0: round-off only)
static constexpr double OVERLAP_FLOOR = 1.0e-6;

/* ---------------------------------------------------------------------- */

LatticeBondRecords::LatticeBondRecords(LAMMPS *lmp, LatticeHeterogeneity &hetero,
                                       const LatticeTimeStep &time_step) :
    Pointers(lmp), hetero(hetero), time_step(time_step), fix_store(nullptr),
    partner_idx(nullptr), partner_nmax(0), partner_stride(0), own_map(0)
{
}

LatticeBondRecords::~LatticeBondRecords()
{
  memory->destroy(partner_idx);
}

/* ----------------------------------------------------------------------
   partners are found by tag: create the global-to-local map if the input
   did not ask for one (atom_modify map)
------------------------------------------------------------------------- */

void LatticeBondRecords::ensure_atom_map()
{
  if (atom->map_style != Atom::MAP_NONE) return;
  if (atom->map_user == Atom::MAP_NONE) atom->map_user = Atom::MAP_YES;
  atom->map_init();
  atom->map_set();
  own_map = 1;
}

/* ----------------------------------------------------------------------
   a neighbour-list pair (a local, b local or ghost) seen from its owner:
   i = the particle with the lower tag, j = its partner.  False if the owner
   is a ghost: its own rank holds the pair as well and records it
------------------------------------------------------------------------- */

bool LatticeBondRecords::owned_pair(int a, int b, int nlocal, const tagint *tag, int &i, int &j)
{
  if (tag[a] < tag[b]) {
    i = a;
    j = b;
    return true;
  }
  if (b < nlocal && tag[b] < tag[a]) {
    i = b;
    j = a;
    return true;
  }
  return false;
}

/* ----------------------------------------------------------------------
   visit(i, j) for every pair of the neighbour list seen from its owner
------------------------------------------------------------------------- */

template <typename Visit> void LatticeBondRecords::for_each_owned_pair(NeighList *list, Visit &&visit)
{
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  for (int ii = 0; ii < list->inum; ii++) {
    const int a = list->ilist[ii];
    if (a >= nlocal) continue;
    const int *jlist = list->firstneigh[a];
    for (int jj = 0; jj < list->numneigh[a]; jj++) {
      int i, j;
      if (owned_pair(a, jlist[jj] & NEIGHMASK, nlocal, tag, i, j)) visit(i, j);
    }
  }
}

/* ---------------------------------------------------------------------- */

bool LatticeBondRecords::has_record_with(int i, tagint partner) const
{
  const tagint *pt = fix_store->partners(i);
  for (int s = 0; s < fix_store->record_count(i); s++)
    if (pt[s] == partner) return true;
  return false;
}

/* ----------------------------------------------------------------------
   first run: every pair closer than (ri + rj)(1 + tolerance) becomes an
   intact bond, stored on the lower tag
------------------------------------------------------------------------- */

void LatticeBondRecords::create_bonds(NeighList *list, const LatticeRadii &radius,
                                      const Bonding &bonding)
{
  double **x = atom->x;
  int *type = atom->type;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  // two passes over the pairs: count each owner's bonds (an upper bound: images
  // of one partner in a small periodic box count twice), size the store for
  // the most any atom has (no growth while bonding), then create them
  std::vector<int> count(nlocal, 0);
  // bonds at either end, counted where both particles are local (interior
  // particles: exact): half the largest is the room a balanced numbering needs
  std::vector<int> coordination(nlocal, 0);
  bigint nbond_local = 0;
  // 2D springs are signed lengths: the store holds one component from the start
  if (domain->dimension == 2) fix_store->set_shear_layout(FixLatticeBondStore::SHEAR_PLANAR);
  for (int pass = 0; pass < 2; pass++) {
    for_each_owned_pair(list, [&](int i, int j) {
      const PairSeparation d = pair_separation(x, i, j);
      const bool bond_pair = bonding.bondable[type[i]][type[j]];
      if (pass == 0) check_overlap(i, j, d.rsq, radius, bond_pair ? &bonding : nullptr);
      if (!bond_pair) return;
      const double reach = radius.touch(i, j) * (1.0 + bonding.tolerance);
      if (d.rsq >= reach * reach) return;
      if (pass == 0) {
        count[i]++;
        coordination[i]++;
        if (j < nlocal) coordination[j]++;
        return;
      }
      // in a small periodic box two images of one partner may be in range
      if (has_record_with(i, tag[j])) return;
      fix_store->add_record(i, tag[j], LB_INTACT);
      nbond_local++;
    });
    if (pass == 0) {
      int most = 0, most_all = 0;
      std::string full;    // the first atom with too many records on this rank
      for (int i = 0; i < nlocal; i++) {
        if (count[i] + fix_store->record_count(i) > fix_store->maxslot() && full.empty())
          full = fmt::format("Atom {} has more than maxslot = {} bonds and contacts ({}); "
                             "increase the pair_style lattice/bond keyword maxslot", tag[i],
                             fix_store->maxslot(), count[i] + fix_store->record_count(i));
        most = MAX(most, count[i] + fix_store->record_count(i));
      }
      lattice_error_from_any_rank(lmp, FLERR, !full.empty(), full);
      MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
      fix_store->fit_capacity(most_all);
    }
  }
  bigint nbond = 0;
  MPI_Allreduce(&nbond_local, &nbond, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  fix_store->mark_bonds_created();
  // the exact room: contacts add more when they need it
  fix_store->fit_capacity(fix_store->global_max_records());
  int most_coord = 0, most_coord_all = 0;
  for (int i = 0; i < nlocal; i++) most_coord = MAX(most_coord, coordination[i]);
  MPI_Allreduce(&most_coord, &most_coord_all, 1, MPI_INT, MPI_MAX, world);
  if (comm->me == 0) {
    const double mean = atom->natoms ? 2.0 * nbond / atom->natoms : 0.0;
    utils::logmesg(lmp, "pair_style lattice/bond: created {} bonds between {} particles (mean "
                   "coordination {:.3f}); room for {} records per particle, {:.2f} used on "
                   "average\n", nbond, atom->natoms, mean, fix_store->capacity(), 0.5 * mean);
    // each bond is stored on the lower ID: a numbering that is not row by row
    // (create_atoms with a multi-atom unit cell) gives some particles more
    // than half their bonds, and every particle that room
    const int balanced = (most_coord_all + 1) / 2;
    if (fix_store->capacity() > balanced)
      utils::logmesg(lmp, "pair_style lattice/bond: the particle numbering gives some particles "
                     "{} records where {} would do; numbering them row by row (bonded-lattice "
                     "generate, or create_atoms with a one-atom primitive cell, 'lattice custom') "
                     "saves memory and time (docs/performance.md)\n", fix_store->capacity(),
                     balanced);
  }
}

/* ----------------------------------------------------------------------
   pair i-j at bonding (rsq: squared distance): coincident atoms (no bond
   direction: NaN) are an error for any pair; a bondable pair must not
   overlap by more than the bonding tolerance (a bond starts at rest at
   r_i + r_j, where the lattice model's particles touch: a pair much closer
   than that has a wrong diameter or position and would start compressed)
------------------------------------------------------------------------- */

void LatticeBondRecords::check_overlap(int i, int j, double rsq, const LatticeRadii &radius,
                                       const Bonding *bonding)
{
  const double touch = radius.touch(i, j);
  const double dist = sqrt(rsq);
  double **x = atom->x;
  const tagint *tag = atom->tag;
  if (dist < COINCIDENT_FRACTION * touch)
    lattice_error_one(
        lmp, FLERR,
        fmt::format("pair_style lattice/bond: atoms {} and {} are at the same position ({} {} {}, "
                    "distance {}): coincident atoms, made twice (two create_atoms commands or "
                    "regions that overlap, a repeated line of a data file). Remove the copies, "
                    "e.g. with delete_atoms overlap {} all all", tag[i], tag[j], x[i][0], x[i][1],
                    x[i][2], dist, 0.5 * touch));
  if (!bonding) return;
  const double tolerance = bonding->tolerance;
  const double limit = MAX(tolerance, OVERLAP_FLOOR);
  if (dist >= touch * (1.0 - limit)) return;
  const double xb = bonding->params[atom->type[i]][atom->type[j]].xb;
  lattice_error_one(
      lmp, FLERR,
      fmt::format("pair_style lattice/bond: atoms {} and {} overlap at bonding: their distance "
                  "{:.6g} is {:.3g}% below r_i + r_j = {:.6g} (radii {:.6g} and {:.6g}), where "
                  "bonded particles touch; the bond would start compressed by {:.3g} (Xb = {:.3g} "
                  "of the type pair). Bonds are made between (r_i + r_j)(1 - t) and (r_i + r_j)"
                  "(1 + t) = {:.6g} to {:.6g} (t = tolerance {}). Check the diameters (a particle "
                  "too large for its lattice spacing) and the positions, or raise the pair_style "
                  "keyword tolerance (< 0.4)",
                  tag[i], tag[j], dist, 100.0 * (1.0 - dist / touch), touch, radius[i], radius[j],
                  touch - dist, xb, touch * (1.0 - limit), touch * (1.0 + tolerance), tolerance));
}

/* ----------------------------------------------------------------------
   after reneighbouring: find each record's partner, drop contacts that have
   separated
------------------------------------------------------------------------- */

void LatticeBondRecords::refresh_partners(const LatticeRadii &radius, double min_radius)
{
  double **x = atom->x;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  // the ghost shell every rank is guaranteed to hold: bonds must fit in it
  const double cutghost = comm->get_comm_cutoff();
  const double cutghost_sq = cutghost * cutghost;

  if (atom->nmax > partner_nmax || partner_stride != fix_store->capacity()) {
    partner_nmax = atom->nmax;
    partner_stride = fix_store->capacity();
    memory->destroy(partner_idx);
    memory->create(partner_idx, (bigint) partner_nmax * partner_stride, "pair:partner_idx");
  }

  // a map made here, after the input's fixes: classes that cached the map style
  // when they were created (Irregular of fix balance) move atoms without
  // updating it, so it is rebuilt from the current local and ghost atoms
  if (own_map) {
    atom->map_clear();
    atom->map_set();
  }

  // records that cannot be used as they are: judged after the loop, over all
  // ranks, so that the message names the real cause (atoms lost from the box,
  // a runaway atom, renumbering) rather than the first symptom found
  RecordTrouble trouble;
  for (int i = 0; i < nlocal; i++) {
    const tagint *pt = fix_store->partners(i);
    const LatticeBondState *st = fix_store->states(i);
    int *idx = partner_idx + (bigint) i * partner_stride;
    // walk downwards so that swap-with-last removal only moves visited records
    for (int s = fix_store->record_count(i) - 1; s >= 0; s--) {
      // records live on the lower ID: a partner ID at or below the owner's
      // means the IDs changed after the record was made
      if (pt[s] <= tag[i]) {
        trouble.note(RecordTrouble::RENUMBERED, tag[i], pt[s], 0.0);
        idx[s] = -1;
        continue;
      }
      int j = atom->map(pt[s]);
      if (j >= 0) j = domain->closest_image(i, j);
      // a stale map entry (deleted atom) must not pass for the partner
      if (j >= 0 && tag[j] != pt[s]) j = -1;
      bool drop = false;
      if (j < 0) {
        if (st[s] == LB_INTACT) trouble.missing.push_back({i, pt[s]});
        drop = (st[s] == LB_CONTACT);
      } else {
        const PairSeparation d = pair_separation(x, i, j);
        const double touch = radius.touch(i, j);
        if (st[s] == LB_INTACT && d.rsq > cutghost_sq)
          trouble.note(RecordTrouble::TOO_LONG, tag[i], pt[s], d.length());
        drop = (st[s] == LB_CONTACT && d.rsq >= touch * touch);
      }
      if (drop) {
        const int last = fix_store->record_count(i) - 1;
        fix_store->remove_record(i, s);
        if (s != last) idx[s] = idx[last];
      } else {
        idx[s] = j;
      }
    }
    if (hetero.enabled()) cache_factors(i);
  }
  // one reduction per reneighbouring: the atom count (atoms lost from the box)
  // and the troubles of every rank
  bigint counts[4] = {nlocal, (bigint) trouble.missing.size(), trouble.count[RecordTrouble::RENUMBERED],
                      trouble.count[RecordTrouble::TOO_LONG]};
  bigint counts_all[4];
  MPI_Allreduce(counts, counts_all, 4, MPI_LMP_BIGINT, MPI_SUM, world);
  if (counts_all[1] + counts_all[2] + counts_all[3] > 0)
    settle_record_trouble(trouble, counts_all, cutghost, min_radius);
}

/* ---------------------------------------------------------------------- */

void LatticeBondRecords::collect_candidates(NeighList *list, const LatticeRadii &radius)
{
  double **x = atom->x;
  const tagint *tag = atom->tag;
  cand_i.clear();
  cand_j.clear();
  cand_min_gap = HUGE_VAL;
  cand_moved = 0.0;
  cand_fresh = true;
  const double skin = neighbor->skin;
  for_each_owned_pair(list, [&](int i, int j) {
    const PairSeparation d = pair_separation(x, i, j);
    const double touch = radius.touch(i, j);
    const double reach = touch + skin;
    if (d.rsq >= reach * reach) return;
    if (has_record_with(i, tag[j])) return;
    // two atoms on top of each other would have no contact normal
    const double near = COINCIDENT_FRACTION * touch;
    if (d.rsq < near * near) check_overlap(i, j, d.rsq, radius, nullptr);
    cand_i.push_back(i);
    cand_j.push_back(j);
    // the gap, less a margin of 1e-9 of the touching distance for the rounding
    // of this and of the bound on the displacements
    cand_min_gap = std::min(cand_min_gap, sqrt(d.rsq) - touch * (1.0 + 1.0e-9));
  });
}

/* ----------------------------------------------------------------------
   records refresh_partners() could not use, on any rank (counts_all: the
   atoms, the intact records whose partner is not here, the renumbered and
   the too long records, summed over the ranks).  Collective; runs only when
   one of those counts is nonzero.  In order:
   1. a partner ID at or below its owner's: the atoms were renumbered;
   2. a partner that is not here and exists nowhere while atoms were lost
      (fewer atoms than atom->natoms: LAMMPS deleted particles that left a
      non-periodic box): the bond went with the atom, the record is dropped
      and a warning says so; LAMMPS itself stops at the next thermo output
      with "Lost atoms" unless thermo_modify lost ignore or warn;
   3. stretched or missing partners during a run: an atom that moved more
      than the instability limit in this step is the cause
      (LatticeTimeStep::stop_if_unstable);
   4. the record's own message
------------------------------------------------------------------------- */

void LatticeBondRecords::settle_record_trouble(RecordTrouble &trouble, const bigint *counts_all,
                                               double cutghost, double min_radius)
{
  using RT = RecordTrouble;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  if (counts_all[2] > 0)
    lattice_error_from_any_rank(
        lmp, FLERR, trouble.count[RT::RENUMBERED] > 0,
        fmt::format("pair_style lattice/bond: the atom IDs changed after the bonds were made: atom "
                    "{} holds the record of its bond to atom {}, but each record is kept on the "
                    "lower ID of its pair, by the IDs the particles had when the bond was made. "
                    "The particles were renumbered (reset_atoms id, or delete_atoms with its "
                    "default compress yes). Bond records name their partners by atom ID: "
                    "renumber before the first run or minimize, which makes the bonds, or not at "
                    "all (delete_atoms ... compress no keeps the IDs)",
                    trouble.owner[RT::RENUMBERED], trouble.partner[RT::RENUMBERED]));

  // partners that are neither local nor ghosts: do they exist on any rank?
  const bigint natoms_before = atom->natoms;
  const bigint natoms_now = counts_all[0];
  bigint dropped = 0;
  if (counts_all[1] > 0) {
    const int nprocs = comm->nprocs;
    // not const: LAMMPS' serial MPI stubs take the send buffers as void *
    int nmine = (int) trouble.missing.size();
    std::vector<int> nper(nprocs), offset(nprocs, 0);
    MPI_Allgather(&nmine, 1, MPI_INT, nper.data(), 1, MPI_INT, world);
    for (int p = 1; p < nprocs; p++) offset[p] = offset[p - 1] + nper[p - 1];
    const int ntotal = offset[nprocs - 1] + nper[nprocs - 1];
    std::vector<tagint> mine(nmine), wanted(ntotal);
    for (int k = 0; k < nmine; k++) mine[k] = trouble.missing[k].second;
    MPI_Allgatherv(mine.data(), nmine, MPI_LMP_TAGINT, wanted.data(), nper.data(), offset.data(),
                   MPI_LMP_TAGINT, world);
    std::vector<int> here(ntotal), exists(ntotal);
    for (int k = 0; k < ntotal; k++) {
      const int m = atom->map(wanted[k]);
      here[k] = (m >= 0 && m < nlocal && tag[m] == wanted[k]) ? 1 : 0;
    }
    MPI_Allreduce(here.data(), exists.data(), ntotal, MPI_INT, MPI_MAX, world);
    const bool atoms_lost = natoms_now < natoms_before;
    for (int k = 0; k < nmine; k++) {
      const int i = trouble.missing[k].first;
      const tagint p = trouble.missing[k].second;
      if (exists[offset[comm->me] + k]) {
        trouble.note(RT::BEYOND, tag[i], p, 0.0);
      } else if (atoms_lost) {
        drop_record(i, p);
        dropped++;
      } else {
        trouble.note(RT::GONE, tag[i], p, 0.0);
      }
    }
    bigint dropped_all = 0;
    MPI_Allreduce(&dropped, &dropped_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (dropped_all > 0 && comm->me == 0)
      error->warning(FLERR, "pair_style lattice/bond: {} particles left the non-periodic box "
                     "and LAMMPS deleted them (Lost atoms: original {} current {}); their {} "
                     "intact bonds are removed. LAMMPS stops at the next thermo output unless "
                     "thermo_modify lost ignore or warn lets them go; to keep the particles, "
                     "make the box larger than the block of particles (LAMMPS deletes atoms that "
                     "cross a fixed boundary, boundary f) or use boundary s or m (shrink-wrapped)",
                     natoms_before - natoms_now, natoms_before, natoms_now, dropped_all);
  }

  bigint rest[3] = {trouble.count[RT::TOO_LONG], trouble.count[RT::BEYOND],
                    trouble.count[RT::GONE]};
  bigint rest_all[3];
  MPI_Allreduce(rest, rest_all, 3, MPI_LMP_BIGINT, MPI_SUM, world);
  if (rest_all[0] + rest_all[1] + rest_all[2] == 0) return;

  // an error is certain: during a run, a particle that moved too far in this
  // step (an unstable integration) is the cause, not the neighbour skin
  const bool setup = update->setupflag;
  if (!setup && update->whichflag != 2) time_step.stop_if_unstable(fix_store, min_radius);

  std::string message;
  const char *when = setup
      ? "At the start of a run: atoms were moved by hand (displace_atoms, set, change_box "
        "without remap) or renumbered (reset_atoms id, delete_atoms ... compress yes) after the "
        "bonds were made, or the bond stretched that far in the previous run"
      : "The intact bond stretched that far in this run (raise neighbor skin or comm_modify "
        "cutoff)";
  if (trouble.count[RT::GONE])
    message = fmt::format("pair_style lattice/bond: bond {}-{} lost its partner: atom {} no longer "
                          "exists. It was deleted (delete_atoms, fix evaporate) or the atoms were "
                          "renumbered (reset_atoms id, delete_atoms ... compress yes) after the "
                          "bonds were made; deleting or renumbering bonded particles is not "
                          "supported",
                          trouble.owner[RT::GONE], trouble.partner[RT::GONE],
                          trouble.partner[RT::GONE]);
  else if (trouble.count[RT::TOO_LONG])
    message = fmt::format("pair_style lattice/bond: bond {}-{} is {} long, beyond the "
                          "communication cutoff {}. {}",
                          trouble.owner[RT::TOO_LONG], trouble.partner[RT::TOO_LONG],
                          trouble.length[RT::TOO_LONG], cutghost, when);
  else if (trouble.count[RT::BEYOND])
    message = fmt::format("pair_style lattice/bond: bond {}-{} is beyond the communication cutoff "
                          "{}: atom {} exists but is neither on this rank nor a ghost. {}",
                          trouble.owner[RT::BEYOND], trouble.partner[RT::BEYOND], cutghost,
                          trouble.partner[RT::BEYOND], when);
  lattice_error_from_any_rank(lmp, FLERR, !message.empty(), message);
}

/* ----------------------------------------------------------------------
   remove the record of local atom i with the given partner
------------------------------------------------------------------------- */

void LatticeBondRecords::drop_record(int i, tagint partner)
{
  const tagint *pt = fix_store->partners(i);
  int *idx = partner_idx + (bigint) i * partner_stride;
  for (int s = 0; s < fix_store->record_count(i); s++)
    if (pt[s] == partner) {
      const int last = fix_store->record_count(i) - 1;
      fix_store->remove_record(i, s);
      if (s != last) idx[s] = idx[last];
      if (hetero.enabled()) cache_factors(i);
      return;
    }
}

/* ----------------------------------------------------------------------
   the heterogeneity factors of local atom i's records (see
   LatticeHeterogeneity::cache_bond_factors)
------------------------------------------------------------------------- */

void LatticeBondRecords::cache_factors(int i)
{
  hetero.cache_bond_factors(i, partner_idx + (bigint) i * partner_stride, fix_store->record_count(i),
                            partner_stride, partner_nmax);
}

/* ----------------------------------------------------------------------
   2D: shear springs stored as vectors in the tangent plane (bond files,
   restart files of format 2) become signed lengths along t = z x n, with
   the sign of their projection on t and their length kept
------------------------------------------------------------------------- */

void LatticeBondRecords::planar_springs_from_vectors()
{
  double **x = atom->x;
  // the signed length goes to component 0; set_shear_layout keeps only it
  const int nc = fix_store->spring_components();
  for (int i = 0; i < atom->nlocal; i++) {
    double *sp = fix_store->springs(i);
    const int *idx = partner_idx + (bigint) i * partner_stride;
    for (int s = 0; s < fix_store->record_count(i); s++) {
      double *sh = sp + s * nc;
      const double len = sqrt(sh[0] * sh[0] + sh[1] * sh[1] + sh[2] * sh[2]);
      const int j = idx[s];
      double sig = 0.0;
      if (j >= 0 && len > 0.0) {
        const PairSeparation d = pair_separation(x, i, j);
        // sign of s . t with t = (-dy, dx) / r: the length r does not matter
        sig = (d.dx * sh[1] - d.dy * sh[0] >= 0.0) ? len : -len;
      }
      sh[0] = sig;
    }
  }
  fix_store->set_shear_layout(FixLatticeBondStore::SHEAR_PLANAR);
}

/* ----------------------------------------------------------------------
   unbonded candidate pairs that now overlap become contact records
------------------------------------------------------------------------- */

void LatticeBondRecords::detect_new_contacts(const LatticeRadii &radius, const double *disp, int n)
{
  // Two atoms closed their gap by at most the sum of their displacements since
  // the collection, so no candidate can touch while twice the largest
  // displacement of any atom here (local or ghost) is below the smallest gap.
  // The bound grows by this step's largest displacement, except in the force
  // evaluation that collected the candidates (its step came before); once it
  // reaches the smallest gap, every candidate is tested at every step, as
  // before the bound, until the next reneighbouring collects them again
  if (cand_fresh) {
    cand_fresh = false;
  } else if (2.0 * cand_moved < cand_min_gap) {
    double largest = 0.0;
    for (int k = 0; k < 3 * n; k += 3)
      largest = std::max(largest, disp[k] * disp[k] + disp[k + 1] * disp[k + 1] +
                                      disp[k + 2] * disp[k + 2]);
    cand_moved += sqrt(largest) * (1.0 + 1.0e-9);
  }
  if (2.0 * cand_moved < cand_min_gap) return;

  double **x = atom->x;
  tagint *tag = atom->tag;

  size_t c = 0;
  while (c < cand_i.size()) {
    const int i = cand_i[c], j = cand_j[c];
    if (pair_touches(pair_separation(x, i, j), radius.touch(i, j))) {
      const int s = fix_store->add_record(i, tag[j], LB_CONTACT);
      if (fix_store->capacity() != partner_stride) relayout_partners();
      partner_idx[(bigint) i * partner_stride + s] = j;
      if (hetero.enabled()) cache_factors(i);
      cand_i[c] = cand_i.back();
      cand_j[c] = cand_j.back();
      cand_i.pop_back();
      cand_j.pop_back();
    } else {
      c++;
    }
  }
}

/* ----------------------------------------------------------------------
   the record store grew: the same partner indices with the new stride
------------------------------------------------------------------------- */

void LatticeBondRecords::relayout_partners()
{
  const int stride = fix_store->capacity();
  int *fresh = nullptr;
  memory->create(fresh, (bigint) partner_nmax * stride, "pair:partner_idx");
  const int nlocal = atom->nlocal;
  const int keep = MIN(stride, partner_stride);
  for (int i = 0; i < nlocal; i++)
    for (int s = 0; s < keep; s++)
      fresh[(bigint) i * stride + s] = partner_idx[(bigint) i * partner_stride + s];
  memory->destroy(partner_idx);
  partner_idx = fresh;
  partner_stride = stride;
  if (hetero.enabled())
    for (int i = 0; i < nlocal; i++) cache_factors(i);
}

/* ---------------------------------------------------------------------- */

double LatticeBondRecords::memory_usage() const
{
  return (double) partner_nmax * partner_stride * sizeof(int) +
      (double) cand_i.capacity() * 2 * sizeof(int);
}

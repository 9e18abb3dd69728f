/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The life of the records of pair_style lattice/bond (one per bond or
   contact, kept by fix LATTICE/BOND/STORE on the particle with the lower
   tag): bonds are created once, at the first run, from the neighbour list;
   after every reneighbouring each record's partner is looked up by tag
   (the partner index the force loop reads), separated contacts are dropped,
   records that cannot be used are judged over all ranks, and the unbonded
   pairs close enough to touch before the next reneighbouring are kept as
   candidates, which become contact records when they overlap.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_BOND_RECORDS_H
#define LMP_LATTICE_BOND_RECORDS_H

#include "lattice_bond_geometry.h"
#include "lattice_bond_physics.h"
#include "pointers.h"

#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class FixLatticeBondStore;
class LatticeHeterogeneity;
class LatticeTimeStep;
class NeighList;

class LatticeBondRecords : protected Pointers {
 public:
  LatticeBondRecords(LAMMPS *lmp, LatticeHeterogeneity &hetero, const LatticeTimeStep &time_step);
  ~LatticeBondRecords() override;

  void attach(FixLatticeBondStore *store) { fix_store = store; }
  void ensure_atom_map();    // a tag -> index map, created if absent

  // which touching pairs become bonds at the first run: those of bondable
  // type pairs closer than (r_i + r_j)(1 + tolerance)
  struct Bonding {
    int **bondable;
    LatticeBondParams **params;    // for the messages
    double tolerance;
  };
  // first run: every such pair of the neighbour list becomes an intact bond
  void create_bonds(NeighList *list, const LatticeRadii &radius, const Bonding &bonding);
  // after reneighbouring: each record's partner, separated contacts dropped,
  // records that cannot be used judged (collective; min_radius: the
  // instability limit of a run)
  void refresh_partners(const LatticeRadii &radius, double min_radius);
  // after refresh_partners: the unbonded pairs within touching distance +
  // skin, the only ones that can come into contact before the next rebuild
  void collect_candidates(NeighList *list, const LatticeRadii &radius);
  bool has_candidates() const { return !cand_i.empty(); }
  bigint candidate_count() const { return (bigint) cand_i.size(); }
  // candidates that now overlap become contact records; disp: this step's
  // displacements of the n local and ghost atoms (the store's, after the
  // forward communication), which bound how far any pair has closed since
  // the candidates were collected: while that bound is below the smallest
  // gap, no candidate can touch and none is tested
  void detect_new_contacts(const LatticeRadii &radius, const double *disp, int n);
  // 2D: shear springs stored as vectors become signed lengths
  void planar_springs_from_vectors();

  // local/ghost index of each record's partner, -1 if absent: record s of
  // atom i at partner_index()[i * stride() + s]
  const int *partner_index() const { return partner_idx; }
  int stride() const { return partner_stride; }
  double memory_usage() const;

 private:
  LatticeHeterogeneity &hetero;
  const LatticeTimeStep &time_step;
  FixLatticeBondStore *fix_store;
  int *partner_idx;    // see partner_index(), refreshed after reneighbouring
  int partner_nmax;
  int partner_stride;  // records per atom in partner_idx (the store's capacity)
  int own_map;         // 1 if this class created the atom map
  std::vector<int> cand_i, cand_j;    // unbonded pairs that may come into contact
  double cand_min_gap = 0.0;    // smallest gap (distance - touching distance) at collection
  double cand_moved = 0.0;      // bound on any atom's displacement since the collection
  bool cand_fresh = false;      // collected in this force evaluation: its step came before

  // records refresh_partners() could not use, judged together after its loop
  struct RecordTrouble {
    enum Kind { RENUMBERED, TOO_LONG, BEYOND, GONE, NKIND };
    bigint count[NKIND] = {0, 0, 0, 0};
    // the first record of each kind: owner and partner IDs, length (TOO_LONG)
    tagint owner[NKIND] = {0, 0, 0, 0}, partner[NKIND] = {0, 0, 0, 0};
    double length[NKIND] = {0.0, 0.0, 0.0, 0.0};
    // intact records whose partner is neither local nor a ghost: (owner index, partner ID)
    std::vector<std::pair<int, tagint>> missing;
    void note(int kind, tagint o, tagint p, double len)
    {
      if (count[kind]++ == 0) {
        owner[kind] = o;
        partner[kind] = p;
        length[kind] = len;
      }
    }
  };
  void settle_record_trouble(RecordTrouble &trouble, const bigint *counts_all, double cutghost,
                             double min_radius);
  void drop_record(int i, tagint partner);
  // pair i-j at bonding or as a candidate: coincident atoms, and the overlap
  // of a bondable pair (bonding: null if the pair does not bond)
  void check_overlap(int i, int j, double rsq, const LatticeRadii &radius, const Bonding *bonding);
  void relayout_partners();
  void cache_factors(int i);
  static bool owned_pair(int a, int b, int nlocal, const tagint *tag, int &i, int &j);
  template <typename Visit> void for_each_owned_pair(NeighList *list, Visit &&visit);
  bool has_record_with(int i, tagint partner) const;
};

}    // namespace LAMMPS_NS

#endif

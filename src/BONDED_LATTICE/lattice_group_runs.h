/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The atoms of a group as runs of consecutive local indices.  A loop over a
   group that is not all can then run the loop compiled for every atom (no
   mask test per atom) over each run.  LAMMPS sorts atoms in space, so the
   atoms of a region (the inner block between two platens, say) lie side by
   side in a few long runs.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_GROUP_RUNS_H
#define LMP_LATTICE_GROUP_RUNS_H

#include "atom.h"
#include "group.h"
#include "lammps.h"
#include "lmptype.h"
#include "neighbor.h"
#include "update.h"

#include <vector>

namespace LAMMPS_NS {

class LatticeGroupRuns {
 public:
  // the runs of the atoms 0..n-1 whose mask has groupbit: one pass over the masks
  void form(const int *mask, int groupbit, int n)
  {
    bounds.clear();
    members = 0;
    int i = 0;
    while (i < n) {
      while (i < n && !(mask[i] & groupbit)) i++;
      if (i == n) break;
      const int first = i;
      while (i < n && (mask[i] & groupbit)) i++;
      bounds.push_back(first);
      bounds.push_back(i);
      members += i - first;
    }
  }

  // the runs of the atoms 0..n-1 in the group, formed again only when the atoms
  // may have been reordered or regrouped since the last call: a neighbour list
  // build since (build: neighbor->lastcall; LAMMPS migrates and sorts atoms only
  // right before one), a new run (run: update->firststep; a run with 'pre no'
  // after a group command has no setup), a new count, or invalidate() (a run's
  // setup).  Whether they are worth looping over (worthwhile)
  bool current(const int *mask, int groupbit, int n, bigint build, bigint run)
  {
    if (stale || n != stamp_n || build != stamp_build || run != stamp_run) {
      form(mask, groupbit, n);
      stale = false;
      stamp_n = n;
      stamp_build = build;
      stamp_run = run;
    }
    return worthwhile();
  }
  void invalidate() { stale = true; }

  // current() for the group igroup (groupbit) among the local atoms 0..n-1 of
  // lmp: never runs for a dynamic group, whose masks change between steps
  bool usable(LAMMPS *lmp, int igroup, int groupbit, int n)
  {
    return !lmp->group->dynamic[igroup] &&
        current(lmp->atom->mask, groupbit, n, lmp->neighbor->lastcall, lmp->update->firststep);
  }

  // whether the runs are long enough (MIN_RUN atoms on average) that a call per
  // run costs less than the mask test per atom it saves
  static constexpr int MIN_RUN = 16;
  bool worthwhile() const { return members >= (long) MIN_RUN * runs(); }
  int runs() const { return (int) bounds.size() / 2; }

  // visit(first, last) for the part of every run within begin..end-1, in order;
  // false if a visit returned false (all are made)
  template <typename Visit> bool each_within(int begin, int end, Visit &&visit) const
  {
    // the first run that ends after begin
    int lo = 0, hi = runs();
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (bounds[2 * mid + 1] <= begin) lo = mid + 1;
      else hi = mid;
    }
    bool ok = true;
    for (int r = lo; r < runs() && bounds[2 * r] < end; r++) {
      const int first = bounds[2 * r] > begin ? bounds[2 * r] : begin;
      const int last = bounds[2 * r + 1] < end ? bounds[2 * r + 1] : end;
      ok = visit(first, last) && ok;
    }
    return ok;
  }

 private:
  std::vector<int> bounds;    // first, last + 1 of each run, in order
  long members = 0;           // atoms in the runs
  bool stale = true;          // see current()
  bigint stamp_build = -1, stamp_run = -1;
  int stamp_n = -1;
};

}    // namespace LAMMPS_NS

#endif

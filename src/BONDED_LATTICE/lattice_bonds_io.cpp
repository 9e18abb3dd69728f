/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   Text export and import of the bond network (see lattice_bonds_io.h).

   File: comment lines starting with #, then one line per record,
       owner partner state shear_x shear_y shear_z
   owner < partner are atom IDs, state is intact, tension (broken in
   tension), shear (broken in shear) or contact (never bonded), shear the
   shear-spring displacement (force on the owner -Ks * shear).  Lines are
   sorted by owner and partner, numbers written with 17 digits.
------------------------------------------------------------------------- */

#include "lattice_bonds_io.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "lammps_api_compat.h"
#include "lattice_errors.h"
#include "pair_lattice_bond.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

static constexpr int FILE_FORMAT = 1;
static const char *const STATE_NAMES[4] = {"intact", "tension", "shear", "contact"};
static constexpr int VALUES = 6;    // owner partner state shear[3], as doubles

static PairLatticeBond *lattice_pair(LAMMPS *lmp, const char *command)
{
  auto *pair = PairLatticeBond::find(lmp->force);
  if (!pair)
    lmp->error->all(FLERR, "{} needs pair_style lattice/bond (the bond network belongs to it)",
                    command);
  return pair;
}

/* ----------------------------------------------------------------------
   one record line: owner partner state shear_x shear_y shear_z, with
   0 < owner < partner, a known state and finite shear; false if it is not
------------------------------------------------------------------------- */

static bool parse_record(const std::string &text, double *record)
{
  const auto words = utils::split_words(text);
  if (words.size() != VALUES || !utils::is_integer(words[0]) || !utils::is_integer(words[1]))
    return false;
  int state = -1;
  for (int k = 0; k < 4; k++)
    if (words[2] == STATE_NAMES[k]) state = k;
  if (state < 0) return false;
  const tagint owner = std::stoll(words[0]), partner = std::stoll(words[1]);
  if (owner < 1 || partner <= owner) return false;
  record[0] = (double) owner;
  record[1] = (double) partner;
  record[2] = state;
  for (int k = 0; k < 3; k++) {
    if (!utils::is_double(words[3 + k])) return false;
    record[3 + k] = std::stod(words[3 + k]);
    if (!std::isfinite(record[3 + k])) return false;
  }
  return true;
}

/* ----------------------------------------------------------------------
   all records of a write_lattice_bonds file into values (VALUES each);
   returns what is wrong with the file, or an empty string
------------------------------------------------------------------------- */

static std::string read_records(const char *path, std::vector<double> &values)
{
  FILE *fp = fopen(path, "r");
  if (!fp) return fmt::format("cannot open file {}: {}", path, utils::getsyserror());
  const std::string header_line = fmt::format("BONDED_LATTICE bond network, format {}", FILE_FORMAT);
  std::string problem;
  char line[512];
  int lineno = 0, header = 0;
  while (problem.empty() && fgets(line, sizeof(line), fp)) {
    lineno++;
    const std::string text = utils::trim(line);
    if (text.empty()) continue;
    if (text[0] == '#') {
      if (text.find("BONDED_LATTICE bond network, format") == std::string::npos) continue;
      header = 1;
      if (text.find(header_line) == std::string::npos)
        problem = fmt::format("line {}: unknown format ({}); this version reads format {}",
                              lineno, text, FILE_FORMAT);
      continue;
    }
    double record[VALUES];
    if (!header)
      problem = fmt::format("line {} comes before the header line '# {}': not a "
                            "write_lattice_bonds file", lineno, header_line);
    else if (!parse_record(text, record))
      problem = fmt::format("line {} is not 'owner partner state shear_x shear_y shear_z' with "
                            "owner < partner, state intact, tension, shear or contact and "
                            "finite shear: {}", lineno, text);
    else
      values.insert(values.end(), record, record + VALUES);
  }
  fclose(fp);
  if (problem.empty() && !header)
    problem = fmt::format("{} has no header line '# {}'", path, header_line);
  return problem;
}

/* ----------------------------------------------------------------------
   write_lattice_bonds file
------------------------------------------------------------------------- */

void WriteLatticeBonds::command(int narg, char **arg)
{
  if (narg != 1) error->all(FLERR, "write_lattice_bonds needs one argument: the file name");
  PairLatticeBond *pair = lattice_pair(lmp, "write_lattice_bonds");
  FixLatticeBondStore *store = pair->store();
  if (!store || !store->bonds_created())
    error->all(FLERR, "write_lattice_bonds: there is no bond network yet; the bonds are made at "
               "the first run (use 'run 0' first)");

  // every rank's records as doubles (IDs fit exactly), gathered on rank 0
  std::vector<double> mine;
  const tagint *tag = atom->tag;
  bigint unknown = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const tagint *pt = store->partners(i);
    const LatticeBondState *st = store->states(i);
    for (int s = 0; s < store->record_count(i); s++) {
      double sh[3];
      if (!pair->shear_vector(i, s, sh)) unknown++;
      mine.insert(mine.end(), {(double) tag[i], (double) pt[s], (double) st[s],
                               sh[0], sh[1], sh[2]});
    }
  }
  bigint unknown_all = 0;
  MPI_Allreduce(&unknown, &unknown_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (unknown_all)
    error->all(FLERR, "write_lattice_bonds: {} loaded 2D shear springs have their partner atom "
               "neither on the owner's rank nor among its ghosts, so their direction is unknown; "
               "write the bonds right after a run (or 'run 0')", unknown_all);
  int count = (int) mine.size();
  std::vector<int> counts(comm->nprocs), offsets(comm->nprocs, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  std::vector<double> all;
  if (comm->me == 0) {
    for (int p = 1; p < comm->nprocs; p++) offsets[p] = offsets[p - 1] + counts[p - 1];
    all.resize(offsets.back() + counts.back());
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
              MPI_DOUBLE, 0, world);
  if (comm->me != 0) return;

  const size_t n = all.size() / VALUES;
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (all[VALUES * a] != all[VALUES * b]) return all[VALUES * a] < all[VALUES * b];
    return all[VALUES * a + 1] < all[VALUES * b + 1];
  });
  std::array<bigint, 4> per_state = {0, 0, 0, 0};
  for (size_t k = 0; k < n; k++) per_state[(int) all[VALUES * k + 2]]++;

  FILE *fp = fopen(arg[0], "w");
  if (!fp)
    lattice_error_one(lmp, FLERR, fmt::format("write_lattice_bonds: cannot open file {}: {}",
                                              arg[0], utils::getsyserror()));
  lattice_print(fp, "# BONDED_LATTICE bond network, format {}\n", FILE_FORMAT);
  lattice_print(fp, "# written at step {} by LAMMPS {}\n", update->ntimestep, lmp->version);
  lattice_print(fp, "# records {}: intact {}, tension {}, shear {}, contact {}\n", n, per_state[0],
                per_state[1], per_state[2], per_state[3]);
  lattice_print(fp, "# owner partner state shear_x shear_y shear_z  (owner: the lower atom ID; "
                "force on the owner -Ks * shear)\n");
  for (size_t k : order) {
    const double *v = &all[VALUES * k];
    lattice_print(fp, "{} {} {} {:.17g} {:.17g} {:.17g}\n", (tagint) v[0], (tagint) v[1],
                  STATE_NAMES[(int) v[2]], v[3], v[4], v[5]);
  }
  fclose(fp);
  utils::logmesg(lmp, "write_lattice_bonds: {} records to {}\n", n, arg[0]);
}

/* ----------------------------------------------------------------------
   read_lattice_bonds file: before the first run, instead of creating the
   bonds from the particles' positions
------------------------------------------------------------------------- */

void ReadLatticeBonds::command(int narg, char **arg)
{
  if (narg != 1) error->all(FLERR, "read_lattice_bonds needs one argument: the file name");
  if (!atom->tag_enable) error->all(FLERR, "read_lattice_bonds needs atom IDs");
  PairLatticeBond *pair = lattice_pair(lmp, "read_lattice_bonds");
  pair->ensure_atom_map();
  FixLatticeBondStore *store = pair->acquire_store();
  if (store->bonds_created())
    error->all(FLERR, "read_lattice_bonds: a bond network exists already (made by a run or "
               "read from a restart file); read the bonds right after read_data and pair_style");

  // rank 0 parses the file, every rank gets the records
  std::vector<double> values;
  std::string problem;
  if (comm->me == 0) problem = read_records(arg[0], values);
  int ok = problem.empty() ? 1 : 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, world);
  if (!ok) lattice_error_from_any_rank(lmp, FLERR, comm->me == 0, "read_lattice_bonds: " + problem);
  bigint n = (bigint) values.size();
  MPI_Bcast(&n, 1, MPI_LMP_BIGINT, 0, world);
  values.resize(n);
  MPI_Bcast(values.data(), (int) n, MPI_DOUBLE, 0, world);

  // the file holds vectors; a 2D run turns them into signed lengths
  store->set_shear_layout(FixLatticeBondStore::SHEAR_VECTOR);
  // each record goes to the rank that owns its owner atom; both atoms must exist
  const bigint nrecords = n / VALUES;
  bigint placed = 0, missing_partner = 0;
  tagint first_missing = 0;
  for (bigint k = 0; k < nrecords; k++) {
    const double *v = &values[VALUES * k];
    // the map holds IDs up to the largest one only: look nothing up beyond it
    if ((tagint) v[0] > atom->map_tag_max) continue;
    const int i = atom->map((tagint) v[0]);
    if (i < 0 || i >= atom->nlocal) continue;
    if ((tagint) v[1] > atom->map_tag_max) {    // beyond the largest atom ID
      if (!missing_partner) first_missing = (tagint) v[1];
      missing_partner++;
    }
    const int s = store->add_record(i, (tagint) v[1], (LatticeBondState) (int) v[2]);
    double *sh = store->springs(i) + 3 * s;
    for (int c = 0; c < 3; c++) sh[c] = v[3 + c];
    placed++;
  }
  bigint placed_all = 0, missing_all = 0;
  MPI_Allreduce(&placed, &placed_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  MPI_Allreduce(&missing_partner, &missing_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (placed_all != nrecords)
    error->all(FLERR, "read_lattice_bonds: {} of the {} records name an owner atom ID that does "
               "not exist; the file does not belong to these atoms", nrecords - placed_all,
               nrecords);
  if (missing_all)
    error->all(FLERR, "read_lattice_bonds: {} records name a partner atom ID that does not exist "
               "(e.g. {}); the file does not belong to these atoms", missing_all, first_missing);
  store->mark_bonds_created();
  if (comm->me == 0)
    utils::logmesg(lmp, "read_lattice_bonds: {} records from {} (no bonds are created from "
                   "positions)\n", nrecords, arg[0]);
}

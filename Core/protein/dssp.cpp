// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/dssp.h"

#include "mesolens/common/errors.h"

#include "common/detail/grid_cells.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <unordered_map>

namespace mesolens {

namespace {
using Vec = std::array<double, 3>;

constexpr double coupling = -27.888;     // -332 * 0.42 * 0.2, kcal/mol Å
constexpr double minimal_distance = 0.5; // Å: closer atoms give the minimal energy
constexpr double minimal_energy = -9.9;  // kcal/mol
constexpr double bond_energy = -0.5;     // kcal/mol: an H-bond below this
constexpr double neighbour_ca = 9.0;     // Å: Cα farther apart form no H-bond
constexpr double peptide_bond = 2.5;     // Å: a longer C-N is a chain break
constexpr double degrees = 180.0 / 3.14159265358979323846;

/// A coordinate triple as an Eigen vector (the residues keep std::array for the public API).
Eigen::Vector3d as_vector(const Vec& a)
{
  return { a[0], a[1], a[2] };
}

double distance(const Vec& a, const Vec& b)
{
  return (as_vector(a) - as_vector(b)).norm();
}

/// The dihedral angle p1-p2-p3-p4, degrees in (-180, 180].
double dihedral(const Vec& p1, const Vec& p2, const Vec& p3, const Vec& p4)
{
  const Eigen::Vector3d b1 = as_vector(p2) - as_vector(p1);
  const Eigen::Vector3d b2 = as_vector(p3) - as_vector(p2);
  const Eigen::Vector3d b3 = as_vector(p4) - as_vector(p3);
  const Eigen::Vector3d n1 = b1.cross(b2);
  const Eigen::Vector3d n2 = b2.cross(b3);
  const Eigen::Vector3d m1 = n1.cross(b2 / b2.norm());
  return -std::atan2(m1.dot(n2), n1.dot(n2)) * degrees;
}

/// The angle between the directions a and b, degrees.
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const double cosine = a.dot(b) / std::sqrt(a.squaredNorm() * b.squaredNorm());
  return std::acos(std::clamp(cosine, -1.0, 1.0)) * degrees;
}

/// The angle at b of a-b-c, degrees.
double angle(const Vec& a, const Vec& b, const Vec& c)
{
  return angle_between(as_vector(a) - as_vector(b), as_vector(c) - as_vector(b));
}

/// The two best (lowest-energy) partners of a donor or an acceptor.
struct BestTwo
{
  std::int64_t partner[2] = { -1, -1 };
  double energy[2] = { 0.0, 0.0 };

  void offer(std::int64_t residue, double value)
  {
    if (value < this->energy[0])
    {
      this->partner[1] = this->partner[0];
      this->energy[1] = this->energy[0];
      this->partner[0] = residue;
      this->energy[0] = value;
    }
    else if (value < this->energy[1])
    {
      this->partner[1] = residue;
      this->energy[1] = value;
    }
  }
  bool bonded_to(std::int64_t residue) const
  {
    return (this->partner[0] == residue && this->energy[0] < bond_energy) ||
      (this->partner[1] == residue && this->energy[1] < bond_energy);
  }
};

enum Helix : std::uint8_t
{
  NoHelix = 0,
  Start = 1,
  End = 2,
  StartAndEnd = 3,
  Middle = 4
};

/// The DSSP computation over the residues with a complete backbone (`used`, in order).
class Dssp
{
public:
  Dssp(const std::vector<BackboneResidue>& residues, const std::vector<std::size_t>& used,
       const std::vector<std::uint8_t>& break_before, const DsspParams& settings)
    : All(residues)
    , Used(used)
    , Settings(settings)
  {
    const std::size_t n = used.size();
    this->Break.assign(n, 0);
    this->Hydrogens.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const BackboneResidue& r = this->At(i);
      // A break before i: a gap in the used list, a flagged break, another chain, or a long
      // peptide bond.
      this->Break[i] = i == 0 || used[i] != used[i - 1] + 1 || break_before[used[i]] ||
          this->At(i - 1).chain != r.chain || distance(this->At(i - 1).c, r.n) > peptide_bond
        ? 1
        : 0;
      // The amide hydrogen: 1 Å from N, opposite the previous carbonyl.
      Vec h = r.n;
      if (settings.file_hydrogens && r.has_h)
      {
        h = r.h;
      }
      else if (!r.proline && i > 0 && !this->Break[i])
      {
        const BackboneResidue& p = this->At(i - 1);
        const Eigen::Vector3d co = as_vector(p.c) - as_vector(p.o);
        const double length = co.norm();
        if (length > 0)
        {
          for (int d = 0; d < 3; ++d)
          {
            h[d] += co[d] / length;
          }
        }
      }
      this->Hydrogens[i] = h;
    }
  }

  const BackboneResidue& At(std::size_t i) const
  {
    return this->All[this->Used[i]];
  }

  /// True when residues a..b (a <= b) have no break between them.
  bool NoBreak(std::size_t a, std::size_t b) const
  {
    for (std::size_t i = a + 1; i <= b; ++i)
    {
      if (this->Break[i])
      {
        return false;
      }
    }
    return true;
  }

  double Energy(std::size_t donor, std::size_t acceptor) const
  {
    const BackboneResidue& d = this->At(donor);
    if (d.proline && !(this->Settings.file_hydrogens && d.has_h))
    {
      return 0.0;
    }
    const BackboneResidue& a = this->At(acceptor);
    const Vec& h = this->Hydrogens[donor];
    const double ho = distance(h, a.o);
    const double hc = distance(h, a.c);
    const double nc = distance(d.n, a.c);
    const double no = distance(d.n, a.o);
    double energy = minimal_energy;
    if (ho >= minimal_distance && hc >= minimal_distance && nc >= minimal_distance &&
        no >= minimal_distance)
    {
      energy = coupling / ho - coupling / hc + coupling / nc - coupling / no;
    }
    // DSSP rounds to 0.001 kcal/mol before comparing.
    energy = std::round(energy * 1000.0) / 1000.0;
    return std::max(energy, minimal_energy);
  }

  void HydrogenBonds(const ParallelFor& parallel_for)
  {
    const std::size_t n = this->Used.size();
    this->Acceptors.assign(n, BestTwo()); // per donor NH: its best C=O partners
    // Cα in cells of 9 Å: pairs within 9 Å are in neighbouring cells.
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    for (std::size_t i = 0; i < n; ++i)
    {
      cells[grid_cell_key(grid_cell(this->At(i).ca, neighbour_ca))].push_back(
        static_cast<std::uint32_t>(i));
    }
    // Per donor, the energies to every acceptor near it (computed in parallel, then offered in
    // a fixed order so that ties resolve the same way every time).
    std::vector<std::vector<std::pair<std::uint32_t, double>>> energies(n);
    run_parallel(parallel_for, n, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
      {
        const Vec& ca = this->At(i).ca;
        const GridCell c = grid_cell(ca, neighbour_ca);
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
            {
              const auto found = cells.find(grid_cell_key(c, dx, dy, dz));
              if (found == cells.end())
              {
                continue;
              }
              for (const std::uint32_t j : found->second)
              {
                // No bond from NH(i) to the C=O of i itself or of i - 1 (DSSP's pairs).
                if (j == i || j + 1 == i || distance(ca, this->At(j).ca) >= neighbour_ca)
                {
                  continue;
                }
                const double energy = this->Energy(i, j);
                if (energy < 0)
                {
                  energies[i].emplace_back(j, energy);
                }
              }
            }
        std::sort(energies[i].begin(), energies[i].end());
      }
    });
    for (std::size_t i = 0; i < n; ++i)
    {
      for (const auto& [j, energy] : energies[i])
      {
        this->Acceptors[i].offer(j, energy);
      }
    }
    this->BondCount = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      for (int k = 0; k < 2; ++k)
      {
        this->BondCount +=
          this->Acceptors[i].partner[k] >= 0 && this->Acceptors[i].energy[k] < bond_energy ? 1 : 0;
      }
    }
  }

  /// N-H of `donor` bonded to C=O of `acceptor`.
  bool Bond(std::int64_t donor, std::int64_t acceptor) const
  {
    if (donor < 0 || acceptor < 0 || donor >= std::int64_t(this->Used.size()) ||
        acceptor >= std::int64_t(this->Used.size()))
    {
      return false;
    }
    return this->Acceptors[std::size_t(donor)].bonded_to(acceptor);
  }

  std::vector<SecondaryStructure> Assign()
  {
    const std::size_t n = this->Used.size();
    std::vector<SecondaryStructure> ss(n, SecondaryStructure::Coil);
    this->Sheets(ss);
    this->Helices(ss);
    this->TurnsAndBends(ss);
    if (this->Settings.polyproline_stretch > 0)
    {
      this->Polyproline(ss);
    }
    return ss;
  }

  std::size_t BondCount = 0;

private:
  enum class Bridge
  {
    None,
    Parallel,
    Antiparallel
  };

  struct Ladder
  {
    Bridge type = Bridge::None;
    std::deque<std::size_t> i;
    std::deque<std::size_t> j;
  };

  Bridge TestBridge(std::size_t i, std::size_t j) const
  {
    const std::size_t n = this->Used.size();
    if (i < 1 || j < 1 || i + 1 >= n || j + 1 >= n || !this->NoBreak(i - 1, i + 1) ||
        !this->NoBreak(j - 1, j + 1))
    {
      return Bridge::None;
    }
    const auto a = std::int64_t(i - 1), b = std::int64_t(i), c = std::int64_t(i + 1);
    const auto d = std::int64_t(j - 1), e = std::int64_t(j), f = std::int64_t(j + 1);
    if ((this->Bond(c, e) && this->Bond(e, a)) || (this->Bond(f, b) && this->Bond(b, d)))
    {
      return Bridge::Parallel;
    }
    if ((this->Bond(c, d) && this->Bond(f, a)) || (this->Bond(e, b) && this->Bond(b, e)))
    {
      return Bridge::Antiparallel;
    }
    return Bridge::None;
  }

  /// a - b as DSSP's unsigned arithmetic sees it: below `limit` only when a >= b.
  static bool GapBelow(std::size_t a, std::size_t b, std::size_t limit)
  {
    return a >= b && a - b < limit;
  }

  /// Bridges (B) and strands (E): the ladders of bridges, joined across bulges.
  void Sheets(std::vector<SecondaryStructure>& ss) const
  {
    std::vector<Ladder> ladders = this->Ladders(this->BridgeCandidates());
    this->JoinAcrossBulges(ladders);
    for (const Ladder& ladder : ladders)
    {
      const SecondaryStructure kind =
        ladder.i.size() > 1 ? SecondaryStructure::Strand : SecondaryStructure::Bridge;
      for (const auto* side : { &ladder.i, &ladder.j })
      {
        const std::size_t low = std::min(side->front(), side->back());
        const std::size_t high = std::max(side->front(), side->back());
        for (std::size_t r = low; r <= high; ++r)
        {
          if (ss[r] != SecondaryStructure::Strand)
          {
            ss[r] = kind;
          }
        }
      }
    }
  }

  /// The residue pairs (i, j) that may form a bridge, in DSSP's order (i, then j).
  std::vector<std::pair<std::size_t, std::size_t>> BridgeCandidates() const
  {
    const std::size_t n = this->Used.size();
    // A bridge (i, j) needs an H-bond between i - 1..i + 1 and j - 1..j + 1: only the pairs
    // near a bond are tested (DSSP tests them all, O(n^2)), in DSSP's order (i, then j).
    std::vector<std::pair<std::size_t, std::size_t>> candidates;
    for (std::size_t donor = 0; donor < n; ++donor)
    {
      for (int k = 0; k < 2; ++k)
      {
        const std::int64_t acceptor = this->Acceptors[donor].partner[k];
        if (acceptor < 0 || this->Acceptors[donor].energy[k] >= bond_energy)
        {
          continue;
        }
        for (int da = -1; da <= 1; ++da)
        {
          for (int db = -1; db <= 1; ++db)
          {
            const std::int64_t a = std::int64_t(donor) + da;
            const std::int64_t b = acceptor + db;
            const std::int64_t i = std::min(a, b);
            const std::int64_t j = std::max(a, b);
            if (i >= 1 && i + 4 < std::int64_t(n) && j >= i + 3 && j + 1 < std::int64_t(n))
            {
              candidates.emplace_back(std::size_t(i), std::size_t(j));
            }
          }
        }
      }
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return candidates;
  }

  /// The bridges among the candidates, gathered into ladders of consecutive bridges.
  std::vector<Ladder> Ladders(
    const std::vector<std::pair<std::size_t, std::size_t>>& candidates) const
  {
    std::vector<Ladder> ladders;
    for (const auto& [i, j] : candidates)
    {
      {
        const Bridge type = this->TestBridge(i, j);
        if (type == Bridge::None)
        {
          continue;
        }
        bool found = false;
        for (Ladder& ladder : ladders)
        {
          if (type != ladder.type || i != ladder.i.back() + 1)
          {
            continue;
          }
          if (type == Bridge::Parallel && ladder.j.back() + 1 == j)
          {
            ladder.i.push_back(i);
            ladder.j.push_back(j);
            found = true;
            break;
          }
          if (type == Bridge::Antiparallel && ladder.j.front() == j + 1)
          {
            ladder.i.push_back(i);
            ladder.j.push_front(j);
            found = true;
            break;
          }
        }
        if (!found)
        {
          Ladder ladder;
          ladder.type = type;
          ladder.i.push_back(i);
          ladder.j.push_back(j);
          ladders.push_back(ladder);
        }
      }
    }
    return ladders;
  }

  /// Ladders of the same type joined across bulges (gaps of up to 1 residue on one strand and
  /// 4 on the other), when the settings allow bulges.
  void JoinAcrossBulges(std::vector<Ladder>& ladders) const
  {
    std::stable_sort(ladders.begin(), ladders.end(),
                     [](const Ladder& x, const Ladder& y) { return x.i.front() < y.i.front(); });
    for (std::size_t a = 0; a < ladders.size(); ++a)
    {
      for (std::size_t b = a + 1; b < ladders.size(); ++b)
      {
        const std::size_t ibi = ladders[a].i.front(), iei = ladders[a].i.back();
        const std::size_t jbi = ladders[a].j.front(), jei = ladders[a].j.back();
        const std::size_t ibj = ladders[b].i.front(), iej = ladders[b].i.back();
        const std::size_t jbj = ladders[b].j.front(), jej = ladders[b].j.back();
        // (mkdssp asks for one chain here, not for no break.)
        if (ladders[a].type != ladders[b].type ||
            this->At(std::min(ibi, ibj)).chain != this->At(std::max(iei, iej)).chain ||
            this->At(std::min(jbi, jbj)).chain != this->At(std::max(jei, jej)).chain ||
            !GapBelow(ibj, iei, 6) || (iei >= ibj && ibi <= iej))
        {
          continue;
        }
        bool bulge = false;
        if (ladders[a].type == Bridge::Parallel)
        {
          bulge = (GapBelow(jbj, jei, 6) && GapBelow(ibj, iei, 3)) || GapBelow(jbj, jei, 3);
        }
        else
        {
          bulge = (GapBelow(jbi, jej, 6) && GapBelow(ibj, iei, 3)) || GapBelow(jbi, jej, 3);
        }
        if (bulge && this->Settings.bulges)
        {
          ladders[a].i.insert(ladders[a].i.end(), ladders[b].i.begin(), ladders[b].i.end());
          if (ladders[a].type == Bridge::Parallel)
          {
            ladders[a].j.insert(ladders[a].j.end(), ladders[b].j.begin(), ladders[b].j.end());
          }
          else
          {
            ladders[a].j.insert(ladders[a].j.begin(), ladders[b].j.begin(), ladders[b].j.end());
          }
          ladders.erase(ladders.begin() + std::ptrdiff_t(b));
          --b;
        }
      }
    }
  }

  void Helices(std::vector<SecondaryStructure>& ss)
  {
    const std::size_t n = this->Used.size();
    for (int stride = 3; stride <= 5; ++stride)
    {
      std::vector<std::uint8_t>& flags = this->HelixFlags[stride - 3];
      flags.assign(n, NoHelix);
      for (std::size_t i = 0; i + std::size_t(stride) < n; ++i)
      {
        const std::size_t end = i + std::size_t(stride);
        if (this->NoBreak(i, end) && this->Bond(std::int64_t(end), std::int64_t(i)))
        {
          flags[end] = End;
          for (std::size_t j = i + 1; j < end; ++j)
          {
            if (flags[j] == NoHelix)
            {
              flags[j] = Middle;
            }
          }
          flags[i] = flags[i] == End ? StartAndEnd : Start;
        }
      }
    }
    auto starts = [&](std::size_t i, int stride) {
      const std::uint8_t flag = this->HelixFlags[stride - 3][i];
      return flag == Start || flag == StartAndEnd;
    };
    for (std::size_t i = 1; i + 4 < n; ++i)
    {
      if (starts(i, 4) && starts(i - 1, 4))
      {
        for (std::size_t j = i; j <= i + 3; ++j)
        {
          ss[j] = SecondaryStructure::AlphaHelix;
        }
      }
    }
    for (std::size_t i = 1; i + 3 < n; ++i)
    {
      if (starts(i, 3) && starts(i - 1, 3))
      {
        bool empty = true;
        for (std::size_t j = i; empty && j <= i + 2; ++j)
        {
          empty = ss[j] == SecondaryStructure::Coil || ss[j] == SecondaryStructure::Helix310;
        }
        if (empty)
        {
          for (std::size_t j = i; j <= i + 2; ++j)
          {
            ss[j] = SecondaryStructure::Helix310;
          }
        }
      }
    }
    for (std::size_t i = 1; i + 5 < n; ++i)
    {
      if (starts(i, 5) && starts(i - 1, 5))
      {
        bool empty = true;
        for (std::size_t j = i; empty && j <= i + 4; ++j)
        {
          empty = ss[j] == SecondaryStructure::Coil || ss[j] == SecondaryStructure::PiHelix ||
            (this->Settings.pi_helix_priority && ss[j] == SecondaryStructure::AlphaHelix);
        }
        if (empty)
        {
          for (std::size_t j = i; j <= i + 4; ++j)
          {
            ss[j] = SecondaryStructure::PiHelix;
          }
        }
      }
    }
  }

  void TurnsAndBends(std::vector<SecondaryStructure>& ss) const
  {
    const std::size_t n = this->Used.size();
    for (std::size_t i = 1; i + 1 < n; ++i)
    {
      if (ss[i] != SecondaryStructure::Coil)
      {
        continue;
      }
      bool turn = false;
      for (int stride = 3; stride <= 5 && !turn; ++stride)
      {
        for (std::size_t k = 1; k < std::size_t(stride) && !turn; ++k)
        {
          const std::uint8_t flag = i >= k ? this->HelixFlags[stride - 3][i - k] : NoHelix;
          turn = flag == Start || flag == StartAndEnd;
        }
      }
      if (turn)
      {
        ss[i] = SecondaryStructure::Turn;
      }
      else if (i >= 2 && i + 2 < n && this->NoBreak(i - 2, i + 2))
      {
        // Kappa: the turn of the chain at i, between CA i-2 -> i and CA i -> i+2.
        const double kappa =
          angle_between(as_vector(this->At(i).ca) - as_vector(this->At(i - 2).ca),
                        as_vector(this->At(i + 2).ca) - as_vector(this->At(i).ca));
        if (kappa > 70.0)
        {
          ss[i] = SecondaryStructure::Bend;
        }
      }
    }
  }

  void Polyproline(std::vector<SecondaryStructure>& ss) const
  {
    const std::size_t n = this->Used.size();
    std::vector<double> phi(n, 360.0);
    std::vector<double> psi(n, 360.0);
    for (std::size_t i = 1; i + 1 < n; ++i)
    {
      if (!this->Break[i])
      {
        phi[i] = dihedral(this->At(i - 1).c, this->At(i).n, this->At(i).ca, this->At(i).c);
      }
      if (!this->Break[i + 1])
      {
        psi[i] = dihedral(this->At(i).n, this->At(i).ca, this->At(i).c, this->At(i + 1).n);
      }
    }
    const auto stretch = std::size_t(this->Settings.polyproline_stretch);
    auto polyproline = [&](std::size_t i) {
      return phi[i] >= -75.0 - 29.0 && phi[i] <= -75.0 + 29.0 && psi[i] >= 145.0 - 29.0 &&
        psi[i] <= 145.0 + 29.0;
    };
    for (std::size_t i = 1; i + stretch < n; ++i)
    {
      bool all = true;
      for (std::size_t k = 0; k < stretch && all; ++k)
      {
        all = polyproline(i + k);
      }
      for (std::size_t k = 0; k < stretch && all; ++k)
      {
        if (ss[i + k] == SecondaryStructure::Coil)
        {
          ss[i + k] = SecondaryStructure::Polyproline;
        }
      }
    }
  }

  const std::vector<BackboneResidue>& All;
  const std::vector<std::size_t>& Used;
  DsspParams Settings;
  std::vector<std::uint8_t> Break;
  std::vector<Vec> Hydrogens;
  std::vector<BestTwo> Acceptors;
  std::array<std::vector<std::uint8_t>, 3> HelixFlags;
};

void require_finite(const Vec& p, std::size_t residue, const char* atom)
{
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
  {
    throw InvalidInput("residue " + std::to_string(residue) + " has a non-finite " + atom +
                       " position");
  }
}
} // namespace

char dssp_letter(SecondaryStructure structure)
{
  switch (structure)
  {
    case SecondaryStructure::AlphaHelix:
    case SecondaryStructure::OtherHelix:
      return 'H';
    case SecondaryStructure::Helix310:
      return 'G';
    case SecondaryStructure::PiHelix:
      return 'I';
    case SecondaryStructure::Strand:
      return 'E';
    case SecondaryStructure::Bridge:
      return 'B';
    case SecondaryStructure::Turn:
      return 'T';
    case SecondaryStructure::Bend:
      return 'S';
    case SecondaryStructure::Polyproline:
      return 'P';
    case SecondaryStructure::Coil:
      break;
  }
  return ' ';
}

SecondaryStructure from_dssp_letter(char letter)
{
  switch (letter)
  {
    case 'H':
      return SecondaryStructure::AlphaHelix;
    case 'G':
      return SecondaryStructure::Helix310;
    case 'I':
      return SecondaryStructure::PiHelix;
    case 'E':
      return SecondaryStructure::Strand;
    case 'B':
      return SecondaryStructure::Bridge;
    case 'T':
      return SecondaryStructure::Turn;
    case 'S':
      return SecondaryStructure::Bend;
    case 'P':
      return SecondaryStructure::Polyproline;
    default:
      return SecondaryStructure::Coil;
  }
}

std::string dssp_string(const std::vector<SecondaryStructure>& structure)
{
  std::string letters(structure.size(), '-');
  for (std::size_t i = 0; i < structure.size(); ++i)
  {
    const char letter = dssp_letter(structure[i]);
    letters[i] = letter == ' ' ? '-' : letter;
  }
  return letters;
}

DsspResult assign_secondary_structure(const std::vector<BackboneResidue>& residues,
                                      const DsspParams& settings, const ParallelFor& parallel_for)
{
  if (settings.polyproline_stretch < 0)
  {
    throw InvalidInput("the polyproline stretch must be 0 (none) or more residues");
  }
  const std::size_t count = residues.size();
  DsspResult result;
  result.structure.assign(count, SecondaryStructure::Coil);
  result.break_before.assign(count, 0);
  result.from_ca_only.assign(count, 0);
  std::vector<std::size_t> used;
  std::unordered_map<int, bool> chain_has_backbone;
  for (std::size_t r = 0; r < count; ++r)
  {
    const BackboneResidue& residue = residues[r];
    if (residue.has_n)
      require_finite(residue.n, r, "N");
    if (residue.has_ca)
      require_finite(residue.ca, r, "CA");
    if (residue.has_c)
      require_finite(residue.c, r, "C");
    if (residue.has_o)
      require_finite(residue.o, r, "O");
    if (residue.has_h && settings.file_hydrogens)
      require_finite(residue.h, r, "H");
    const bool complete = residue.has_n && residue.has_ca && residue.has_c && residue.has_o;
    chain_has_backbone[residue.chain] = chain_has_backbone[residue.chain] || complete;
    result.break_before[r] = r == 0 || residues[r - 1].chain != residue.chain || !complete ||
        !(residues[r - 1].has_n && residues[r - 1].has_ca && residues[r - 1].has_c &&
          residues[r - 1].has_o) ||
        distance(residues[r - 1].c, residue.n) > peptide_bond
      ? 1
      : 0;
    if (complete)
    {
      used.push_back(r);
    }
  }
  if (!used.empty())
  {
    Dssp dssp(residues, used, result.break_before, settings);
    dssp.HydrogenBonds(parallel_for);
    const std::vector<SecondaryStructure> assigned = dssp.Assign();
    for (std::size_t i = 0; i < used.size(); ++i)
    {
      result.structure[used[i]] = assigned[i];
    }
    result.hydrogen_bonds = dssp.BondCount;
  }
  // Chains without a single complete backbone residue: from their Cα atoms.
  std::vector<std::array<double, 3>> ca;
  std::vector<int> chain;
  std::vector<std::size_t> ca_residue;
  for (std::size_t r = 0; r < count; ++r)
  {
    if (!chain_has_backbone[residues[r].chain] && residues[r].has_ca)
    {
      ca.push_back(residues[r].ca);
      chain.push_back(residues[r].chain);
      ca_residue.push_back(r);
    }
  }
  if (!ca.empty())
  {
    const std::vector<SecondaryStructure> assigned = assign_from_ca(ca, chain);
    for (std::size_t k = 0; k < ca.size(); ++k)
    {
      result.structure[ca_residue[k]] = assigned[k];
      result.from_ca_only[ca_residue[k]] = 1;
    }
  }
  return result;
}

std::vector<SecondaryStructure> assign_from_ca(PointSpan<const double> ca,
                                               const std::vector<int>& chain)
{
  const std::size_t n = ca.size();
  if (chain.size() != n)
  {
    throw InvalidInput("assign_from_ca needs one chain index per Cα");
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    require_finite(ca.point(i), i, "CA");
  }
  // Consecutive Cα of one chain are 3.8 Å apart; farther is a break.
  auto linked = [&](std::size_t a, std::size_t b) {
    for (std::size_t i = a + 1; i <= b; ++i)
    {
      if (chain[i] != chain[i - 1] || distance(ca.point(i), ca.point(i - 1)) > 4.2)
      {
        return false;
      }
    }
    return true;
  };
  std::vector<SecondaryStructure> ss(n, SecondaryStructure::Coil);
  std::vector<std::uint8_t> helical(n, 0);
  std::vector<std::uint8_t> extended(n, 0);
  for (std::size_t i = 1; i + 2 < n; ++i)
  {
    if (!linked(i - 1, i + 2))
    {
      continue;
    }
    const double tau = angle(ca.point(i - 1), ca.point(i), ca.point(i + 1));
    const double alpha = dihedral(ca.point(i - 1), ca.point(i), ca.point(i + 1), ca.point(i + 2));
    const double d3 = distance(ca.point(i - 1), ca.point(i + 2));
    helical[i] =
      std::abs(tau - 89.0) <= 12.0 && std::abs(alpha - 50.0) <= 20.0 && d3 >= 4.5 && d3 <= 6.0 ? 1
                                                                                               : 0;
    extended[i] = std::abs(tau - 124.0) <= 14.0 && std::abs(alpha) >= 120.0 ? 1 : 0;
  }
  // Helices: 4 or more helical residues in a row, with the flanking residue of each window.
  for (std::size_t i = 1; i + 3 < n; ++i)
  {
    if (helical[i] && helical[i + 1] && helical[i + 2] && helical[i + 3])
    {
      for (std::size_t j = i; j <= std::min(n - 1, i + 4); ++j)
      {
        ss[j] = SecondaryStructure::AlphaHelix;
      }
    }
  }
  // Strands: 3 or more extended residues in a row, each beside an extended residue elsewhere.
  std::vector<std::uint8_t> paired(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!extended[i])
      continue;
    for (std::size_t j = 0; j < n && !paired[i]; ++j)
    {
      const std::size_t gap = i > j ? i - j : j - i;
      if (gap >= 3 && extended[j] && distance(ca.point(i), ca.point(j)) <= 5.5)
      {
        paired[i] = 1;
      }
    }
  }
  for (std::size_t i = 0; i + 2 < n; ++i)
  {
    if (extended[i] && extended[i + 1] && extended[i + 2] && linked(i, i + 2) &&
        (paired[i] || paired[i + 1] || paired[i + 2]))
    {
      for (std::size_t j = i; j <= i + 2; ++j)
      {
        if (ss[j] == SecondaryStructure::Coil)
        {
          ss[j] = SecondaryStructure::Strand;
        }
      }
    }
  }
  return ss;
}

SecondaryStructureHysteresis::SecondaryStructureHysteresis(int frames)
  : Frames(frames)
{
  if (frames < 1)
  {
    throw InvalidInput("the hysteresis needs at least 1 frame, not " + std::to_string(frames));
  }
}

const std::vector<SecondaryStructure>& SecondaryStructureHysteresis::update(
  const std::vector<SecondaryStructure>& frame)
{
  if (frame.size() != this->Shown.size())
  {
    this->Shown = frame;
    this->Candidate = frame;
    this->Held.assign(frame.size(), this->Frames);
    return this->Shown;
  }
  for (std::size_t i = 0; i < frame.size(); ++i)
  {
    if (frame[i] == this->Shown[i])
    {
      this->Candidate[i] = frame[i];
      this->Held[i] = 0;
      continue;
    }
    this->Held[i] = frame[i] == this->Candidate[i] ? this->Held[i] + 1 : 1;
    this->Candidate[i] = frame[i];
    if (this->Held[i] >= this->Frames)
    {
      this->Shown[i] = frame[i];
    }
  }
  return this->Shown;
}

} // namespace mesolens

// ContactBins: the contacts of particle bodies dealt into two bins that share no body, each taking
// its contacts and ground points in the order of the lists (contact_bins.h).
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "physics/contact_bins.h"

namespace {

using phys::BodyId;
using phys::ContactBins;

phys::Manifold manifold(int a, int b, std::uint32_t first, std::uint32_t count) {
  phys::Manifold m;
  m.a = BodyId(a);
  m.b = BodyId(b);
  m.firstContact = first;
  m.contactCount = count;
  return m;
}

// `perBody` ground points for each of `bodies` bodies, in body order, then `loose` loose particles'.
std::vector<phys::GroundContact> groundPoints(int bodies, int perBody, int loose) {
  std::vector<phys::GroundContact> points;
  for (int b = 0; b < bodies; ++b) {
    for (int k = 0; k < perBody; ++k) {
      phys::GroundContact g;
      g.body = BodyId(b);
      points.push_back(g);
    }
  }
  for (int k = 0; k < loose; ++k) points.emplace_back();
  return points;
}

// The indices a bin's ranges cover, checked to be in increasing order.
std::vector<std::uint32_t> covered(std::span<const ContactBins::Range> ranges) {
  std::vector<std::uint32_t> out;
  for (const ContactBins::Range& r : ranges) {
    EXPECT_LT(r.begin, r.end);
    if (!out.empty()) {
      EXPECT_GT(r.begin, out.back());
    }
    for (std::uint32_t k = r.begin; k < r.end; ++k) out.push_back(k);
  }
  return out;
}

// Each body's contacts and ground points in one bin only, every one of them in a bin.
void expectDisjointAndWhole(const ContactBins& bins, std::span<const phys::Manifold> manifolds,
                            std::span<const phys::GroundContact> ground) {
  std::vector<BodyId> contactBody;  // per contact: body a of its manifold
  for (const phys::Manifold& m : manifolds) {
    for (std::uint32_t k = 0; k < m.contactCount; ++k) contactBody.push_back(m.a);
  }
  std::set<std::uint32_t> bodies[2];
  std::size_t contacts = 0, points = 0;
  for (int bin = 0; bin < 2; ++bin) {
    for (const std::uint32_t k : covered(bins.contactRanges(bin))) {
      ++contacts;
      for (const phys::Manifold& m : manifolds) {
        if (k >= m.firstContact && k < m.firstContact + m.contactCount) {
          bodies[bin].insert(m.a);
          bodies[bin].insert(m.b);
        }
      }
    }
    for (const std::uint32_t k : covered(bins.groundRanges(bin))) {
      ++points;
      if (ground[k].body != phys::kNoBody) bodies[bin].insert(ground[k].body);
    }
  }
  EXPECT_EQ(contacts, contactBody.size());
  EXPECT_EQ(points, ground.size());
  for (const std::uint32_t b : bodies[0])
    EXPECT_EQ(bodies[1].count(b), 0u) << "body " << b << " in both bins";
}

// Two rows of four bodies, each row joined along itself by contacts, the rows apart: one row a bin.
TEST(ContactBins, TwoGroupsApartGoOneToEachBin) {
  const std::vector<phys::Manifold> manifolds = {manifold(0, 1, 0, 4),  manifold(1, 2, 4, 4),
                                                 manifold(2, 3, 8, 4),  manifold(4, 5, 12, 4),
                                                 manifold(5, 6, 16, 4), manifold(6, 7, 20, 4)};
  const std::vector<phys::GroundContact> ground = groundPoints(8, 2, 0);
  ContactBins bins;
  ASSERT_TRUE(bins.deal(manifolds, ground, 8));
  expectDisjointAndWhole(bins, manifolds, ground);
  // Each bin's contacts in one range, and its ground points in one: the rows are consecutive.
  ASSERT_EQ(bins.contactRanges(0).size(), 1u);
  EXPECT_EQ(bins.contactRanges(0)[0].begin, 0u);
  EXPECT_EQ(bins.contactRanges(0)[0].end, 12u);
  ASSERT_EQ(bins.groundRanges(1).size(), 1u);
  EXPECT_EQ(bins.groundRanges(1)[0].begin, 8u);
  EXPECT_EQ(bins.groundRanges(1)[0].end, 16u);
}

// A contact between the rows joins them: one group, all the work in one bin, so not dealt.
TEST(ContactBins, OneGroupIsNotDealt) {
  const std::vector<phys::Manifold> manifolds = {
      manifold(0, 1, 0, 4),  manifold(1, 2, 4, 4),  manifold(2, 3, 8, 4), manifold(3, 4, 12, 1),
      manifold(4, 5, 13, 4), manifold(5, 6, 17, 4), manifold(6, 7, 21, 4)};
  const std::vector<phys::GroundContact> ground = groundPoints(8, 2, 0);
  ContactBins bins;
  EXPECT_FALSE(bins.deal(manifolds, ground, 8));
  EXPECT_FALSE(bins.dealt());
  EXPECT_TRUE(bins.contactRanges(0).empty());
}

// Groups taken in the order of their first bodies: interleaved groups (0, 2, 4 joined; 1, 3, 5
// joined) still share no body, each bin's contacts in the lists' order.
TEST(ContactBins, InterleavedGroupsShareNoBody) {
  const std::vector<phys::Manifold> manifolds = {manifold(0, 2, 0, 3), manifold(1, 3, 3, 3),
                                                 manifold(2, 4, 6, 3), manifold(3, 5, 9, 3)};
  const std::vector<phys::GroundContact> ground = groundPoints(6, 1, 0);
  ContactBins bins;
  ASSERT_TRUE(bins.deal(manifolds, ground, 6));
  expectDisjointAndWhole(bins, manifolds, ground);
  EXPECT_EQ(bins.contactRanges(0).size(), 2u);  // contacts 0-2 and 6-8
  EXPECT_EQ(bins.groundRanges(0).size(), 3u);   // bodies 0, 2 and 4
}

// A loose particle's ground point is its own owner: it goes to the bin with less work so far.
TEST(ContactBins, LooseParticlesGoToTheLighterBin) {
  const std::vector<phys::Manifold> manifolds = {manifold(0, 1, 0, 4), manifold(2, 3, 4, 2)};
  const std::vector<phys::GroundContact> ground = groundPoints(4, 1, 4);  // points 4 to 7 loose
  ContactBins bins;
  ASSERT_TRUE(bins.deal(manifolds, ground, 4));
  expectDisjointAndWhole(bins, manifolds, ground);
  // Bin 0 holds bodies 0 and 1 (4 contacts, 2 points), bin 1 bodies 2 and 3 (2 and 2): bin 1 takes
  // loose points until it is no lighter.
  const std::vector<std::uint32_t> second = covered(bins.groundRanges(1));
  EXPECT_EQ(second, (std::vector<std::uint32_t>{2, 3, 4, 5, 7}));
}

// The later substeps: manifolds gone, the others' contacts moved up, ranged by the bins dealt.
TEST(ContactBins, RangedAgainAfterManifoldsGo) {
  const std::vector<phys::Manifold> dealt = {manifold(0, 1, 0, 4), manifold(2, 3, 4, 4),
                                             manifold(4, 5, 8, 4)};
  const std::vector<phys::GroundContact> ground = groundPoints(6, 1, 0);
  ContactBins bins;
  ASSERT_TRUE(bins.deal(dealt, ground, 6));
  const int binOfFirst = bins.contactRanges(0).empty() || bins.contactRanges(0)[0].begin != 0 ? 1 : 0;
  const std::vector<phys::Manifold> later = {manifold(0, 1, 0, 4), manifold(4, 5, 4, 2)};
  bins.rangeContacts(later);
  expectDisjointAndWhole(bins, later, ground);
  EXPECT_EQ(covered(bins.contactRanges(binOfFirst)).front(), 0u);
}

}  // namespace

#pragma once
// Reading a scene's <expect> elements, for the stability suite's pass criteria
// (stability_criteria.h) and the accuracy runs' analytic answers (accuracy.h) alike: strictly,
// like the scene loader reads an element, so a scene file's typo is named and not ignored.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace lab {

/// The place in bodyPositions() (bodies.h) of the body the scene names `name`; none if it names
/// no box or loose particle.
std::optional<std::size_t> bodySlot(const scenes::Scene& scene, const std::string& name);

/// Reads one <expect>'s attributes: every attribute asked for is remembered, so anything left over
/// is named as unknown with the known ones listed. Errors are scenes::LoadErrors naming the
/// file, the <expect>'s line and the attribute.
class ExpectReader {
 public:
  /// `element` opens every message: "<expect>", "<expect kind=\"position\">".
  ExpectReader(const scenes::Expectation& x, std::string file, std::string element);

  [[noreturn]] void fail(const std::string& attribute, const std::string& message) const;
  const std::string* find(const std::string& name);
  /// Fails "is required", with what it should be in brackets unless `what` is empty.
  const std::string& required(const std::string& name, const std::string& what = "");
  /// Fails on an attribute not asked for ("unknown attribute" + `scope`), or given twice.
  void rejectUnknown(const std::string& scope = "") const;

 private:
  const scenes::Expectation& x_;
  std::string file_, element_;
  std::vector<std::string> asked_;
};

}  // namespace lab

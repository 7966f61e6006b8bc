#include "batch_refusal.hpp"

#include <fmt/format.h>

#include <cmath>
#include <regex>

namespace odocal {
namespace {

// The same reason with each wheel's own numbers ("0.77 mm of it" against "0.78 mm of it").
bool same_reason(const std::string& a, const std::string& b) {
  static const std::regex number("[-+]?[0-9][0-9.e+-]*");
  return std::regex_replace(a, number, "#") == std::regex_replace(b, number, "#");
}

std::string sigma_text(double sigma_m) {
  return std::isfinite(sigma_m) ? fmt::format("{:.3g} mm", 1e3 * sigma_m)
                                : std::string("not computable");
}

}  // namespace

std::string circumference_refusal(const std::vector<EstimatedParameter>& parameters,
                                  double max_sigma_circumference_m, bool rank_deficient) {
  std::vector<const EstimatedParameter*> refused;
  for (std::size_t w = 0; w < 2 && w < parameters.size(); ++w)
    if (!parameters[w].identified) refused.push_back(&parameters[w]);
  if (refused.empty() && !rank_deficient) return "";

  std::string text = "not identified: ";
  if (rank_deficient) text += kRankDeficientReason;
  if (refused.empty()) return text;
  if (rank_deficient) text += "; ";
  for (std::size_t k = 0; k < refused.size(); ++k) {
    text += fmt::format("{}{} 1-sigma {}", k == 0 ? "" : ", ", refused[k]->name,
                        sigma_text(refused[k]->sigma));
  }
  text += fmt::format(" (max_sigma_circumference_m {:.3g} mm): {}", 1e3 * max_sigma_circumference_m,
                      refused.front()->verdict);
  if (refused.size() == 2 && !same_reason(refused[0]->verdict, refused[1]->verdict))
    text += fmt::format("; {}: {}", refused[1]->name, refused[1]->verdict);
  return text;
}

}  // namespace odocal

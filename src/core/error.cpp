#include "volspline/core/error.h"

namespace volspline {

namespace {
std::string compose(const std::string& message, const std::string& where) {
  return where.empty() ? message : where + ": " + message;
}
}  // namespace

InvalidInput::InvalidInput(std::string message, std::string where)
    : Error(compose(message, where)), message_(std::move(message)), where_(std::move(where)) {}

InvalidInput InvalidInput::located(const std::string& prefix) const {
  std::string joined = prefix;
  if (!where_.empty() && where_.front() != '[' && !joined.empty()) joined += '.';
  joined += where_;
  return InvalidInput(message_, joined);
}

}  // namespace volspline

#include "sixdof_planning/errors.h"

namespace sixdof_planning {

ErrorCode makeError(int val, const std::string& message, const std::string& source) {
  ErrorCode code;
  code.val = val;
  code.message = message;
  code.source = source;
  return code;
}

ErrorCode makeSuccess(const std::string& source, const std::string& message) {
  return makeError(ErrorCode::SUCCESS, message, source);
}

ErrorCode recode(ErrorCode code, int val) {
  if (code.val == ErrorCode::FAILURE) code.val = val;
  return code;
}

}  // namespace sixdof_planning

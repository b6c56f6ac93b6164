// error_code_names.h against the message definition: every constant of moveit_msgs/MoveItErrorCodes.msg has its
// name and value in the table, and the table has nothing else.
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "sixdof_msgs/error_code_names.h"

namespace {

// name -> value of the `int32 NAME=VALUE` constants of a .msg file.
std::map<std::string, int32_t> messageConstants(const std::string& path) {
  std::ifstream file(path);
  EXPECT_TRUE(file) << "cannot read " << path;
  const std::regex constant(R"(^\s*int32\s+([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(-?[0-9]+)\s*(#.*)?$)");
  std::map<std::string, int32_t> constants;
  std::string line;
  std::smatch match;
  while (std::getline(file, line)) {
    if (std::regex_match(line, match, constant)) constants[match[1]] = std::stoi(match[2]);
  }
  return constants;
}

TEST(ErrorCodeNames, TableIsExactlyTheMessageConstants) {
  const auto constants = messageConstants(MOVEIT_ERROR_CODES_MSG);
  ASSERT_FALSE(constants.empty()) << "no int32 constants in " << MOVEIT_ERROR_CODES_MSG;
  std::map<std::string, int32_t> table;
  std::set<int32_t> values;
  for (const auto& entry : sixdof_msgs::kMoveItErrorCodeNames) {
    EXPECT_TRUE(table.emplace(entry.name, entry.val).second) << entry.name << " is in the table twice";
    EXPECT_TRUE(values.insert(entry.val).second) << "value " << entry.val << " is in the table twice";
  }
  EXPECT_EQ(table, constants);
  EXPECT_EQ(sixdof_msgs::kMoveItErrorCodeNames.size(), constants.size());
}

TEST(ErrorCodeNames, NamesOfKnownAndUnknownValues) {
  for (const auto& [name, val] : messageConstants(MOVEIT_ERROR_CODES_MSG)) {
    EXPECT_EQ(sixdof_msgs::errorCodeName(val), name);
  }
  EXPECT_EQ(sixdof_msgs::errorCodeName(moveit_msgs::MoveItErrorCodes::NO_IK_SOLUTION), "NO_IK_SOLUTION");
  EXPECT_EQ(sixdof_msgs::errorCodeName(0), "unknown MoveIt error code 0");
  EXPECT_EQ(sixdof_msgs::errorCodeName(-1234), "unknown MoveIt error code -1234");
}

}  // namespace

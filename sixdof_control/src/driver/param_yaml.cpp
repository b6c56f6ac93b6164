#include "param_yaml.h"

#include <sstream>
#include <stdexcept>

namespace sixdof_control {

YAML::Node toYaml(XmlRpc::XmlRpcValue& value, const std::string& where) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return YAML::Node(static_cast<bool>(value));
    case XmlRpc::XmlRpcValue::TypeInt:
      return YAML::Node(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble: {
      std::ostringstream text;
      text.precision(17);
      text << static_cast<double>(value);
      return YAML::Load(text.str());
    }
    case XmlRpc::XmlRpcValue::TypeString:
      return YAML::Node(static_cast<std::string>(value));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node list(YAML::NodeType::Sequence);
      for (int i = 0; i < value.size(); ++i) list.push_back(toYaml(value[i], where + "[" + std::to_string(i) + "]"));
      return list;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto& member : value) map[member.first] = toYaml(member.second, where + "/" + member.first);
      return map;
    }
    case XmlRpc::XmlRpcValue::TypeInvalid:
      return YAML::Node();
    default:
      throw std::runtime_error("parameter '" + where + "' is not a YAML value (base64 or date)");
  }
}

YAML::Node paramYaml(const ros::NodeHandle& nh, const std::string& key) {
  XmlRpc::XmlRpcValue value;
  if (!nh.getParam(key, value)) return YAML::Node();
  return toYaml(value, nh.resolveName(key));
}

}  // namespace sixdof_control

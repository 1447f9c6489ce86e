// Doubles in JSON outputs and journals: finite values as numbers (nlohmann prints the shortest
// form that round-trips), the others as "inf", "-inf" and "nan" strings, since JSON has none.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace depthprec {

nlohmann::json json_number(double v);
// what: the field's name in the error a bad value raises (InputError).
double number_from_json(const nlohmann::json& v, const std::string& what);

}  // namespace depthprec

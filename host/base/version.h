#pragma once
namespace depthprec {
constexpr const char* kVersion = "0.1.0";
}

// XML 1.0 text and attribute values, for every XML the tools write (JUnit reports, SVG plots).
#pragma once

#include <string>
#include <string_view>

namespace tmcl {

// The five escapes, and control bytes (not allowed in XML 1.0, apart from tab and line breaks)
// left out, so that a program or file name holding one cannot make the document unreadable.
std::string xml_text(std::string_view s);

}  // namespace tmcl

// json_output.h - json_string: any bytes as a quoted JSON string, for the tools' JSON output (dsn-bake
// --report, dsn-inspect --json). Part of libdsn_tools.a.
#ifndef DSN_TOOLS_JSON_OUTPUT_H
#define DSN_TOOLS_JSON_OUTPUT_H

#include <string>

namespace dsn {

// `text` quoted and escaped as a JSON string. Bytes that are not UTF-8 (a file name may hold any bytes)
// become U+FFFD, so the output is always valid UTF-8 JSON.
std::string json_string(const std::string &text);

} // namespace dsn

#endif // DSN_TOOLS_JSON_OUTPUT_H

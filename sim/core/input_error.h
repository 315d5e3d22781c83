// The one error type for bad input anywhere in pelage. Library code throws it; only the
// CLI's main() catches it and exits with code 2 (docs/design.md, "Conventions").
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace pelage {

class InputError : public std::runtime_error {
  public:
    // file: the offending file (or "" when the input is not a file);
    // line: 1-based line number, 0 when unknown; field: a JSON path or field name.
    InputError(std::string file, std::size_t line, std::string field, std::string message)
        : std::runtime_error(format(file, line, field, message)),
          m_file(std::move(file)),
          m_line(line),
          m_field(std::move(field)) {}

    const std::string &file() const { return m_file; }
    std::size_t line() const { return m_line; }
    const std::string &field() const { return m_field; }

  private:
    static std::string format(const std::string &file, std::size_t line,
                              const std::string &field, const std::string &message) {
        std::string s = file;
        if (line > 0) {
            s += ':';
            s += std::to_string(line);
        }
        if (!field.empty()) {
            if (!s.empty()) s += ": ";
            s += field;
        }
        if (!s.empty()) s += ": ";
        s += message;
        return s;
    }

    std::string m_file;
    std::size_t m_line;
    std::string m_field;
};

}  // namespace pelage

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
          m_field(std::move(field)),
          m_message(std::move(message)) {}

    const std::string &file() const { return m_file; }
    std::size_t line() const { return m_line; }
    const std::string &field() const { return m_field; }
    const std::string &message() const { return m_message; }

    // The same error with its field inside `prefix`: a block a reader parses on its own
    // ("regions.head") where it sits in a larger file ("objects[0].fur.regions.head").
    InputError under(const std::string &prefix) const {
        return InputError(m_file, m_line,
                          m_field.empty() ? prefix : prefix + "." + m_field, m_message);
    }

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
    std::string m_message;
};

}  // namespace pelage

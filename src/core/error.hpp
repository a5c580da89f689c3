// Errors crossing a stage boundary: one line `penink: <stage>: <file>: <what is wrong>`
// (conventions.md), with the process exit code: 2 for bad input, 1 for internal failure.
#pragma once
#include <ostream>
#include <stdexcept>
#include <string>

namespace penink {

enum class ExitCode : int { ok = 0, internal = 1, bad_input = 2 };

class Error : public std::runtime_error {
public:
    Error(std::string stage, std::string file, const std::string& what,
          ExitCode code = ExitCode::bad_input);
    const std::string& stage() const { return stage_; }
    const std::string& file() const { return file_; }
    ExitCode code() const { return code_; }

private:
    std::string stage_, file_;
    ExitCode code_;
};

// A number as error messages quote it: printf's %g (six significant digits, no trailing zeros).
std::string message_number(double v);

// "penink: stage: file: what" (the file part is left out when file is empty).
std::string format_error(const std::string& stage, const std::string& file, const std::string& what);

// A command's run(): its exit code, or its error written to `log` as one line (an Error as it is,
// any other exception as `penink: stage: file: what`, internal) and that error's exit code.
template <class Run> int run_reporting_errors(std::ostream& log, const std::string& stage, const std::string& file, Run&& run) {
    try {
        return run();
    } catch (const Error& e) {
        log << e.what() << "\n";
        return int(e.code());
    } catch (const std::exception& e) {
        log << format_error(stage, file, e.what()) << "\n";
        return int(ExitCode::internal);
    }
}

}  // namespace penink

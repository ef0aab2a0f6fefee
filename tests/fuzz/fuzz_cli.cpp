// libFuzzer: isolux-cli's command line, parsed and run: each line of the
// input is one argument. Arguments naming a path with a '/' are skipped (the
// files a command writes stay in this fuzzer's own empty folder), as is
// --allow-huge (work without a budget); everything else runs as a user's
// command line would, budgets included.
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

int isolux_cli_main(int argc, char** argv);

namespace {
char folder[] = "/tmp/isolux_fuzz_cli_XXXXXX";
void remove_folder() {
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (!::mkdtemp(folder) || ::chdir(folder) != 0) std::abort();
    std::atexit(remove_folder);  // what the commands wrote goes with it
    // The command's own output is not the fuzzer's.
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 4096) return 0;
    std::vector<std::string> args = {"isolux-cli"};
    std::string arg;
    for (std::size_t i = 0; i <= size; ++i) {
        if (i == size || data[i] == '\n') {
            args.push_back(arg);
            arg.clear();
            if (args.size() > 40) return 0;
        } else {
            arg.push_back(char(data[i]));
        }
    }
    for (const std::string& a : args)
        if (a.find('/') != std::string::npos || a.find("allow-huge") != std::string::npos) return 0;
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    isolux_cli_main(int(args.size()), argv.data());
    return 0;
}

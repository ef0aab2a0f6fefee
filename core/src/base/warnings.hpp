// Warnings of one kind, capped: the first few in full, then how many more.
// A file with a million faulty entries gives a dozen lines, not a million
// (nor a million strings in memory).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace isolux {

class WarningRun {
public:
    // `more`: what the count line calls the rest ("edits outside the map").
    WarningRun(std::vector<std::string>* out, std::string more, std::size_t shown = 10)
        : out_(out), more_(std::move(more)), shown_(shown) {}
    WarningRun(const WarningRun&) = delete;
    WarningRun& operator=(const WarningRun&) = delete;
    ~WarningRun() {
        if (out_ && count_ > shown_)
            out_->push_back("and " + std::to_string(count_ - shown_) + " more " + more_);
    }
    // Whether the next warning is shown: when false, the caller need not
    // even build its text.
    bool wanted() const { return out_ && count_ < shown_; }
    void add(std::string text) {
        if (wanted()) out_->push_back(std::move(text));
        ++count_;
    }
    std::size_t count() const { return count_; }

private:
    std::vector<std::string>* out_;
    std::string more_;
    std::size_t shown_;
    std::size_t count_ = 0;
};

}  // namespace isolux

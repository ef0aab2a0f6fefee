// Values built once per key and kept for the next caller while the bytes
// they hold stay within a budget: past it, the least recently used are
// dropped (a caller still using one keeps it alive through its shared_ptr).
// The tracers keep their ray trees so: a scene's lights mostly share a few
// shapes, but a scene of many lights of distinct areas, or an area slider
// dragged through every value, would otherwise keep every tree it built
// (about 50 MB each at a = b = 512). Thread-safe; a value is built under the
// lock, one build at a time.
#pragma once
#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>

namespace isolux {

template <class Key, class Value>
class BoundedCache {
public:
    explicit BoundedCache(std::size_t budget_bytes) : budget_(budget_bytes) {}

    // The value for `key`: kept, else build() (a shared_ptr to it), whose
    // size bytes(value) tells. The newest stays even when alone over budget.
    template <class Build, class Bytes>
    std::shared_ptr<const Value> get(const Key& key, Build&& build, Bytes&& bytes) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (auto it = index_.find(key); it != index_.end()) {
            order_.splice(order_.begin(), order_, it->second);  // now the most recently used
            return it->second->value;
        }
        std::shared_ptr<const Value> value = build();
        order_.push_front(Entry{key, value, bytes(*value)});
        index_[key] = order_.begin();
        held_ += order_.front().bytes;
        while (held_ > budget_ && order_.size() > 1) {
            held_ -= order_.back().bytes;
            index_.erase(order_.back().key);
            order_.pop_back();
        }
        return value;
    }

    std::size_t bytes_held() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return held_;
    }
    std::size_t size() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return order_.size();
    }

private:
    struct Entry {
        Key key;
        std::shared_ptr<const Value> value;
        std::size_t bytes;
    };
    mutable std::mutex mutex_;
    std::list<Entry> order_;  // most recently used first
    std::map<Key, typename std::list<Entry>::iterator> index_;
    const std::size_t budget_;
    std::size_t held_ = 0;
};

// The bytes a vector's elements take.
template <class V>
std::size_t vector_bytes(const V& v) {
    return v.capacity() * sizeof(typename V::value_type);
}

}  // namespace isolux

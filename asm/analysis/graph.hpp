// Strongly connected components (Tarjan, without recursion: call chains of a million regions
// must not overflow the C++ stack), over any graph given as a successor function. Used for the
// call graph (recursion, longest call chain) and the instruction graph (EEPROM writes in loops).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace tmcl::detail {

// succ(v, k) gives the k-th successor of v (k = 0, 1, ...), or -1 after the last: no list of
// successors is built (an instruction has at most two). Returns the component of every vertex
// of `roots`' reach (-1 elsewhere); components are numbered in the order Tarjan completes them,
// so every edge leads to a component with a number no larger than its own (callees before
// callers). `done(c, members, comp)`, when given, is called as component c completes, with its
// vertices and the components so far (every component an edge of theirs leads to has completed
// before), so a pass over the components in that order needs no sort of its own.
struct NoComponentCallback {
  void operator()(int, std::span<const int>, const std::vector<int>&) const {}
};
template <class Succ, class Done = NoComponentCallback>
std::vector<int> strong_components(int n, const std::vector<int>& roots, Succ succ, int& count, Done done = {}) {
  std::vector<int> index(static_cast<std::size_t>(n), -1), low(static_cast<std::size_t>(n), 0),
      comp(static_cast<std::size_t>(n), -1);
  std::vector<int> stack;
  struct Frame {
    int v;
    int next;  // the successor to look at next
  };
  std::vector<Frame> frames;
  int counter = 0;
  count = 0;
  auto open = [&](int v) {
    index[static_cast<std::size_t>(v)] = low[static_cast<std::size_t>(v)] = counter++;
    stack.push_back(v);
    frames.push_back({v, 0});
  };
  for (int root : roots) {
    if (root < 0 || root >= n || index[static_cast<std::size_t>(root)] >= 0) continue;
    open(root);
    while (!frames.empty()) {
      Frame& f = frames.back();
      if (int w = succ(f.v, f.next); w >= 0) {
        ++f.next;
        if (w >= n) continue;
        if (index[static_cast<std::size_t>(w)] < 0) {
          open(w);
        } else if (comp[static_cast<std::size_t>(w)] < 0) {
          low[static_cast<std::size_t>(f.v)] = std::min(low[static_cast<std::size_t>(f.v)], index[static_cast<std::size_t>(w)]);
        }
        continue;
      }
      int v = f.v;
      frames.pop_back();
      if (low[static_cast<std::size_t>(v)] == index[static_cast<std::size_t>(v)]) {
        std::size_t first = stack.size() - 1;
        while (stack[first] != v) --first;
        for (std::size_t k = first; k < stack.size(); ++k) comp[static_cast<std::size_t>(stack[k])] = count;
        done(count, std::span<const int>(stack.data() + first, stack.size() - first), comp);
        stack.resize(first);
        ++count;
      }
      if (!frames.empty()) {
        int p = frames.back().v;
        low[static_cast<std::size_t>(p)] = std::min(low[static_cast<std::size_t>(p)], low[static_cast<std::size_t>(v)]);
      }
    }
  }
  return comp;
}

}  // namespace tmcl::detail

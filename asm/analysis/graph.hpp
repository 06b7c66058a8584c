// Strongly connected components (Tarjan, without recursion: call chains of a million regions
// must not overflow the C++ stack), over any graph given as a successor function. Used for the
// call graph (recursion, longest call chain) and the instruction graph (EEPROM writes in loops).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace tmcl::detail {

// succ(v, k) gives the k-th successor of v (k = 0, 1, ...), or -1 after the last: no list of
// successors is built (an instruction has at most two). Returns the component of every vertex
// of `roots`' reach (-1 elsewhere); components are numbered in the order Tarjan completes them,
// so every edge leads to a component with a number no larger than its own (callees before
// callers).
template <class Succ>
std::vector<int> strong_components(int n, const std::vector<int>& roots, Succ succ, int& count) {
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
        for (;;) {
          int w = stack.back();
          stack.pop_back();
          comp[static_cast<std::size_t>(w)] = count;
          if (w == v) break;
        }
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

#include "app/study/counterbalancing.h"

#include <algorithm>
#include <stdexcept>

namespace cb {

std::optional<CounterbalanceScheme> counterbalanceSchemeFromName(std::string_view name) {
  if (name == "fixed") return CounterbalanceScheme::kFixed;
  if (name == "rotation") return CounterbalanceScheme::kRotation;
  if (name == "williams") return CounterbalanceScheme::kWilliams;
  return std::nullopt;
}

std::string_view counterbalanceSchemeName(CounterbalanceScheme scheme) {
  switch (scheme) {
    case CounterbalanceScheme::kFixed:
      return "fixed";
    case CounterbalanceScheme::kRotation:
      return "rotation";
    case CounterbalanceScheme::kWilliams:
      return "williams";
  }
  return "?";
}

int counterbalanceCycle(CounterbalanceScheme scheme, int task_count) {
  switch (scheme) {
    case CounterbalanceScheme::kFixed:
      return 1;
    case CounterbalanceScheme::kRotation:
      return std::max(task_count, 1);
    case CounterbalanceScheme::kWilliams:
      return task_count % 2 == 0 ? std::max(task_count, 1) : 2 * task_count;
  }
  return 1;
}

std::vector<int> taskOrderForParticipant(CounterbalanceScheme scheme, int task_count,
                                         int participant_number) {
  if (task_count < 0 || participant_number < 1)
    throw std::invalid_argument("taskOrderForParticipant: participants are numbered from 1");
  const int n = task_count;
  std::vector<int> order(n);
  if (n == 0) return order;
  const int row = (participant_number - 1) % counterbalanceCycle(scheme, n);
  for (int j = 0; j < n; ++j) {
    switch (scheme) {
      case CounterbalanceScheme::kFixed:
        order[j] = j;
        break;
      case CounterbalanceScheme::kRotation:
        order[j] = (row + j) % n;
        break;
      case CounterbalanceScheme::kWilliams: {
        // First row 0, 1, n-1, 2, n-2, ...; row r adds r (mod n).
        const int first = j == 0 ? 0 : (j % 2 == 1 ? (j + 1) / 2 : n - j / 2);
        order[j] = (first + row % n) % n;
        break;
      }
    }
  }
  if (scheme == CounterbalanceScheme::kWilliams && n % 2 == 1 && row >= n)
    std::reverse(order.begin(), order.end());
  return order;
}

}  // namespace cb

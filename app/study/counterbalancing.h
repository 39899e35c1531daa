// Task order across participants (thesis §7.5 gave every participant the same four images in
// one order; a study that compares orders counterbalances them). Schemes:
//   fixed     every participant takes the tasks in the declared order
//   rotation  cyclic Latin square: participant N starts at task (N-1) mod n; each task is in
//             each position once per cycle of n participants
//   williams  balanced Latin square (Williams 1949, "Experimental designs balanced for the
//             estimation of residual effects of treatments", Aust. J. Sci. Res. 2(3)): as
//             rotation, and each task also follows each other task equally often; a cycle is n
//             participants for even n, 2n for odd n (the second half mirrors the first)
// Participants are numbered from 1 (the participant id counter, participant_ids.h).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace cb {

enum class CounterbalanceScheme { kFixed, kRotation, kWilliams };

std::optional<CounterbalanceScheme> counterbalanceSchemeFromName(std::string_view name);
std::string_view counterbalanceSchemeName(CounterbalanceScheme scheme);

// Participants after which the orders repeat (1 for fixed).
int counterbalanceCycle(CounterbalanceScheme scheme, int task_count);

// Participant `participant_number`'s (>= 1) task order: indices into the declared task list.
std::vector<int> taskOrderForParticipant(CounterbalanceScheme scheme, int task_count,
                                         int participant_number);

}  // namespace cb

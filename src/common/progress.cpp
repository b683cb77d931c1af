#include <pcl_sparse/common/progress.h>

#include <cstdio>
#include <memory>
#include <unistd.h>

namespace pcl_sparse
{
  ProgressCallback
  makeConsoleProgress (bool quiet)
  {
    if (quiet)
      return {};
    struct State
    {
      std::string stage;
      int percent = -1;
    };
    auto state = std::make_shared<State> ();
    const bool terminal = ::isatty (::fileno (stderr)) != 0;
    return [state, terminal] (const std::string& stage, double fraction) {
      const int percent = static_cast<int> (fraction * 100.0 + 1e-9);
      if (stage == state->stage && percent == state->percent)
        return;
      if (!terminal && stage == state->stage && percent < 100 && percent / 10 == state->percent / 10)
        return;  // in logs, one line per 10 %
      if (terminal && !state->stage.empty () && stage != state->stage)
        std::fputc ('\n', stderr);
      state->stage = stage;
      state->percent = percent;
      std::fprintf (stderr, terminal ? "\r%s: %3d%%" : "%s: %3d%%\n", stage.c_str (), percent);
      if (terminal && percent >= 100)
        std::fputc ('\n', stderr), state->stage.clear ();
      std::fflush (stderr);
    };
  }
} // namespace pcl_sparse

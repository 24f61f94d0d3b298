#include "hb/errors.h"

#include <utility>

namespace beamid {
namespace {

std::string ComposeMessage(const std::string& file, const std::string& channel, const std::string& problem,
                           const std::string& fix) {
  std::string message = file;
  if (!channel.empty()) message += ": channel '" + channel + "'";
  message += ": " + problem;
  if (!fix.empty()) message += ". Fix: " + fix;
  return message;
}

}  // namespace

InputError::InputError(std::string file, std::string channel, const std::string& problem, const std::string& fix)
    : std::invalid_argument(ComposeMessage(file, channel, problem, fix)),
      file_(std::move(file)),
      channel_(std::move(channel)) {}

}  // namespace beamid

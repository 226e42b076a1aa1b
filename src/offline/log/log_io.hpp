// Convenience include: everything for tpf logs (Log, read_log, write_log, LogWriter).
#pragma once

#include "offline/log/log.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"

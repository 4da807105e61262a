// AddressSanitizer's defaults for the fuzz targets and the replay test (ASAN_OPTIONS adds to them).
// An input whose memory grows without end must end its run within seconds: the hard RSS limit
// aborts the process (libFuzzer saves the input first), where libFuzzer's own -rss_limit_mb first
// prints a heap profile, which takes minutes on such a heap.
extern "C" const char* __asan_default_options() { return "hard_rss_limit_mb=1024"; }

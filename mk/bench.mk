# Benchmarks (make bench): filled in as benchmarks land.

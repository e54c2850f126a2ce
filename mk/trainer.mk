# Trainer (C++17): filled in by the trainer work (issue 3).

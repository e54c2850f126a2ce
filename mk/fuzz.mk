# Fuzzing (tests/fuzz/): a libFuzzer target over message decode, map
# ingestion and planning. `make fuzz` runs it for FUZZ_SECONDS from the
# committed seed corpus (new inputs go to build/fuzz/corpus, never into the
# repository); `make test` replays the corpus under ASan+UBSan (gcc, no
# clang needed). `make fuzz-corpus` regenerates the seeds.
FUZZ_SECONDS ?= 60
# libFuzzer needs clang.
FUZZ_CC ?= clang
FUZZ_SRCS := tests/fuzz/fuzz_plan.c $(ONBOARD_SRCS) onboard/msg/convert.c onboard/msg/wire.c \
	$(MSG_NOPUBSUB_SRCS)
FUZZ_INC := $(ONBOARD_INC) -Ionboard/msg -I$(LCM_GEN_DIR)/c-nopubsub -Itests
FUZZ_REPLAY := $(BUILD)/san/test/fuzz/fuzz_replay
FUZZ_BIN := $(BUILD)/fuzz/fuzz_plan
FUZZ_CORPUS := $(sort $(wildcard tests/fuzz/corpus/*))

# The replay links the sanitizer build's objects (the generated lcm-gen code
# among them is exempt from the nonnull check, see mk/msgs.mk).
$(FUZZ_REPLAY): tests/fuzz/fuzz_plan.c $(MSG_NOPUBSUB_OBJS_SAN) $(MSG_ADAPT_LIB_SAN) $(ONBOARD_LIB_SAN) \
		tests/onboard/testutil_planner.h
	@mkdir -p $(@D)
	$(CC) -std=c99 -ffp-contract=off $(CPPFLAGS) $(CFLAGS) $(LDFLAGS) -O1 -g -DFUZZ_REPLAY $(SAN_FLAGS) \
		$(FUZZ_INC) $< $(MSG_NOPUBSUB_OBJS_SAN) $(MSG_ADAPT_LIB_SAN) $(ONBOARD_LIB_SAN) -lm -o $@

$(FUZZ_BIN): $(FUZZ_SRCS) $(LCM_STAMP) tests/onboard/testutil_planner.h
	@mkdir -p $(@D)
	$(FUZZ_CC) -std=c99 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize=nonnull-attribute \
		$(FUZZ_INC) $(filter %.c,$^) -lm -o $@

tests/fuzz/test_corpus.sh: $(FUZZ_REPLAY)
ALL_TARGETS += $(FUZZ_REPLAY)
TESTS_SAN += tests/fuzz/test_corpus.sh

$(FUZZ_BIN): | fuzz-deps
fuzz-deps:
	@tools/install-deps clang libclang-rt-14-dev

fuzz: deps $(FUZZ_BIN)
	@mkdir -p $(BUILD)/fuzz/corpus
	$(FUZZ_BIN) -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 -timeout=10 \
		$(BUILD)/fuzz/corpus tests/fuzz/corpus

FUZZ_CORPUS_GEN := $(BUILD)/fuzz/make_corpus
$(FUZZ_CORPUS_GEN): tests/fuzz/make_corpus.c onboard/msg/convert.c $(MSG_NOPUBSUB_SRCS) $(ONBOARD_LIB) $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) -std=c99 -ffp-contract=off $(CPPFLAGS) $(CFLAGS) $(LDFLAGS) -O1 -g $(FUZZ_INC) tests/fuzz/make_corpus.c onboard/msg/convert.c $(MSG_NOPUBSUB_SRCS) $(ONBOARD_LIB) -lm -o $@

fuzz-corpus: $(FUZZ_CORPUS_GEN)
	@mkdir -p tests/fuzz/corpus
	$(FUZZ_CORPUS_GEN) tests/fuzz/corpus

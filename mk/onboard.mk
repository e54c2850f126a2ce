# Onboard planner (C99): the planning core library, its tests, in a normal and
# an ASan+UBSan build.
#   build/lib/libhylo.a            core library (-O2)
#   build/san/lib/libhylo.a        the same under ASan+UBSan
#   build/test/onboard/test_*      one CMocka binary per module (tests/onboard/)
#   build/san/test/onboard/test_*  the same binaries under ASan+UBSan

ONBOARD_INC := -Ionboard/include -Ionboard
# The API (hylo/*.h) and the workspace's layout (hylo/internal/*.h: struct
# hylo_planner embeds their types; not API). Both are installed; the core's
# own private header, onboard/src/planner_internal.h, is not.
ONBOARD_PUBLIC_HEADERS := $(sort $(wildcard onboard/include/hylo/*.h))
ONBOARD_INTERNAL_HEADERS := $(sort $(wildcard onboard/include/hylo/internal/*.h))
ONBOARD_HEADERS := $(ONBOARD_PUBLIC_HEADERS) $(ONBOARD_INTERNAL_HEADERS)
ONBOARD_SRCS := \
	onboard/src/status.c \
	onboard/src/types.c \
	onboard/src/rng.c \
	$(filter-out onboard/src/status.c onboard/src/types.c onboard/src/rng.c,$(sort $(wildcard onboard/src/*.c)))
ONBOARD_OBJS := $(ONBOARD_SRCS:%.c=$(BUILD)/obj/%.o)
ONBOARD_OBJS_SAN := $(ONBOARD_SRCS:%.c=$(BUILD)/san/obj/%.o)
ONBOARD_LIB := $(BUILD)/lib/libhylo.a
ONBOARD_LIB_SAN := $(BUILD)/san/lib/libhylo.a

$(BUILD)/obj/onboard/%.o: onboard/%.c
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(DEP_FLAGS) $(ONBOARD_INC) -c $< -o $@

$(BUILD)/san/obj/onboard/%.o: onboard/%.c
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(ONBOARD_INC) -c $< -o $@

$(ONBOARD_LIB): $(ONBOARD_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(ONBOARD_LIB_SAN): $(ONBOARD_OBJS_SAN)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

# Message adaptors (decoded LCM types <-> core views): kept out of the core
# so that the core needs no LCM header.
MSG_ADAPT_SRCS := onboard/msg/convert.c onboard/msg/wire.c
MSG_ADAPT_LIB := $(BUILD)/lib/libhylo_msg.a
MSG_ADAPT_LIB_SAN := $(BUILD)/san/lib/libhylo_msg.a
MSG_ADAPT_INC := -Ionboard/msg -I$(LCM_GEN_DIR)/c-nopubsub

$(BUILD)/obj/onboard/msg/%.o: onboard/msg/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(DEP_FLAGS) $(ONBOARD_INC) $(MSG_ADAPT_INC) -c $< -o $@

$(BUILD)/san/obj/onboard/msg/%.o: onboard/msg/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(ONBOARD_INC) $(MSG_ADAPT_INC) -c $< -o $@

$(MSG_ADAPT_LIB): $(MSG_ADAPT_SRCS:%.c=$(BUILD)/obj/%.o)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(MSG_ADAPT_LIB_SAN): $(MSG_ADAPT_SRCS:%.c=$(BUILD)/san/obj/%.o)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

# Unit tests: tests/onboard/test_<module>.c. They may use the generated
# message types (no liblcm) and libsvm as a reference.
ONBOARD_TEST_SRCS := $(sort $(wildcard tests/onboard/test_*.c))
ONBOARD_TEST_NAMES := $(basename $(notdir $(ONBOARD_TEST_SRCS)))
ONBOARD_TESTS := $(ONBOARD_TEST_NAMES:%=$(BUILD)/test/onboard/%)
ONBOARD_TESTS_SAN := $(ONBOARD_TEST_NAMES:%=$(BUILD)/san/test/onboard/%)
TEST_INC := $(ONBOARD_INC) $(MSG_ADAPT_INC) -Itests -Ionboard/models $(CMOCKA_CFLAGS)
TEST_LIBS := $(SVM_LIBS) $(CMOCKA_LIBS) -lm
# The allocation test wraps the allocator at link time (tests/onboard/test_nomalloc.c).
WRAP_ALLOC := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free
TEST_LDFLAGS_test_nomalloc := $(WRAP_ALLOC)

$(BUILD)/obj/tests/%.o: tests/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(DEP_FLAGS) $(TEST_INC) -c $< -o $@

$(BUILD)/san/obj/tests/%.o: tests/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(TEST_INC) -c $< -o $@

$(BUILD)/test/onboard/%: $(BUILD)/obj/tests/onboard/%.o $(MSG_ADAPT_LIB) $(ONBOARD_LIB) $(MSG_NOPUBSUB_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $< $(MSG_NOPUBSUB_OBJS) $(MSG_ADAPT_LIB) $(ONBOARD_LIB) $(TEST_LDFLAGS_$*) $(TEST_LIBS) -o $@

$(BUILD)/san/test/onboard/%: $(BUILD)/san/obj/tests/onboard/%.o $(MSG_ADAPT_LIB_SAN) $(ONBOARD_LIB_SAN) $(MSG_NOPUBSUB_OBJS_SAN)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $(SAN_FLAGS) $< $(MSG_NOPUBSUB_OBJS_SAN) $(MSG_ADAPT_LIB_SAN) $(ONBOARD_LIB_SAN) $(TEST_LDFLAGS_$*) $(TEST_LIBS) -o $@

# Capacity test: the core compiled for small capacities that ordinary test
# scenes exceed (tests/capacity/).
CAPACITY_FLAGS := -DHYLO_MAX_POSITIONS=400 -DHYLO_MAX_NODES=2000 -DHYLO_MAX_ADJACENCY=6000 \
	-DHYLO_MAX_SUCCESSORS=250 -DHYLO_MAX_WAYPOINTS=12 -DHYLO_MAX_SV=64 -DHYLO_MAX_COMBOS=32
CAPACITY_TEST := $(BUILD)/test/capacity/test_capacity
CAPACITY_TEST_SAN := $(BUILD)/san/test/capacity/test_capacity

$(CAPACITY_TEST): tests/capacity/test_capacity.c $(ONBOARD_SRCS) $(ONBOARD_HEADERS) $(wildcard tests/onboard/*.h)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) $(CAPACITY_FLAGS) $(ONBOARD_INC) -Itests tests/capacity/test_capacity.c $(ONBOARD_SRCS) $(TEST_LIBS) -o $@

$(CAPACITY_TEST_SAN): tests/capacity/test_capacity.c $(ONBOARD_SRCS) $(ONBOARD_HEADERS) $(wildcard tests/onboard/*.h)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) $(SAN_FLAGS) $(CAPACITY_FLAGS) $(ONBOARD_INC) -Itests tests/capacity/test_capacity.c $(ONBOARD_SRCS) $(TEST_LIBS) -o $@

ALL_TARGETS += $(CAPACITY_TEST) $(CAPACITY_TEST_SAN)
TESTS += $(CAPACITY_TEST)
TESTS_SAN += $(CAPACITY_TEST_SAN)

ALL_TARGETS += $(ONBOARD_LIB) $(ONBOARD_LIB_SAN) $(MSG_ADAPT_LIB) $(MSG_ADAPT_LIB_SAN) $(ONBOARD_TESTS) $(ONBOARD_TESTS_SAN)
TESTS += $(ONBOARD_TESTS)
TESTS_SAN += $(ONBOARD_TESTS_SAN)


# The toy mode of tests/toymode/ (a mode added in one header): the onboard
# library and the trainer built with it, for tests/toymode/test_toy_mode.sh.
#   build/toy/lib/libhylo.a   the library with mode 6, "toy"
#   build/toy/bin/trainer     the trainer with its model
TOY_DIR := $(BUILD)/toy
TOY_FLAGS := -DHYLO_EXTRA_MODES_H='"toymode/toy_mode.h"' -Itests
TOY_LIB := $(TOY_DIR)/lib/libhylo.a
TOY_TRAINER := $(TOY_DIR)/bin/trainer
TOY_ONBOARD_OBJS := $(ONBOARD_SRCS:%.c=$(TOY_DIR)/obj/%.o)
# Trainer sources that see no mode (no hylo/ header, no robot parameters)
# are the normal build's objects.
TOY_SHARED_SRCS := trainer/files.cpp trainer/numerics.cpp trainer/processes.cpp trainer/sha256.cpp
TOY_TRAINER_OBJS := $(filter-out $(TOY_SHARED_SRCS),$(TRAINER_SRCS)) trainer/main.cpp
TOY_TRAINER_OBJS := $(TOY_TRAINER_OBJS:%.cpp=$(TOY_DIR)/obj/%.o) $(TOY_SHARED_SRCS:%.cpp=$(BUILD)/obj/%.o)

$(TOY_DIR)/obj/onboard/%.o: onboard/%.c tests/toymode/toy_mode.h
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(DEP_FLAGS) $(TOY_FLAGS) $(ONBOARD_INC) -c $< -o $@

$(TOY_LIB): $(TOY_ONBOARD_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(TOY_DIR)/obj/trainer/%.o: trainer/%.cpp tests/toymode/toy_mode.h
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(TOY_FLAGS) -c $< -o $@

$(TOY_TRAINER): $(TOY_TRAINER_OBJS) $(TOY_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(LDFLAGS) $^ $(TRAINER_LIBS) -o $@

ALL_TARGETS += $(TOY_LIB) $(TOY_TRAINER)

TOY_TEST := tests/toymode/test_toy_mode.sh
$(TOY_TEST): $(TOY_LIB) $(TOY_TRAINER)
TESTS += $(TOY_TEST)

#include <gtest/gtest.h>
#include <slepcsys.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  const int result = RUN_ALL_TESTS();
  PetscCall(SlepcFinalize());
  return result;
}

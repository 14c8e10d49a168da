// Placeholder until the dataset readers land; removed with them.

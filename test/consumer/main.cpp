// A downstream program built against the installed mrepair package.
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>

#include <iostream>

int main()
{
  mrepair::Report r;
  r.add("status", mrepair::Status::ok);
  std::cout << r.to_json() << "\n";
  return mrepair::succeeded(mrepair::Status::ok) ? 0 : 1;
}

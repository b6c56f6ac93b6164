#pragma once

#include <memory>

#include <rviz/panel.h>

#include "sixdof_rviz/planning_panel_logic.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;

namespace sixdof_rviz {

// "sixdof_rviz/MotionPlanningPanel": widgets only; every decision and ROS call is in PlanningPanelLogic.
class MotionPlanningPanel : public rviz::Panel {
  Q_OBJECT
 public:
  explicit MotionPlanningPanel(QWidget* parent = nullptr);
  ~MotionPlanningPanel() override;

  void onInitialize() override;
  void load(const rviz::Config& config) override;
  void save(rviz::Config config) const override;

 private Q_SLOTS:
  void groupChanged();
  void goalSourceChanged();
  void planClicked();
  void executeClicked();
  void planAndExecuteClicked();
  void stopClicked();

 private:
  PlanningSettings settings() const;
  GoalSpec goalSpec() const;
  void showStatus(const PanelStatus& status);
  void applySavedChoices();
  void initFailed(const std::string& text);

  QComboBox* group_combo_;
  QComboBox* goal_source_combo_;
  QComboBox* named_state_combo_;
  QComboBox* planner_combo_;
  QDoubleSpinBox* planning_time_spin_;
  QSpinBox* attempts_spin_;
  QDoubleSpinBox* velocity_spin_;
  QDoubleSpinBox* acceleration_spin_;
  QPushButton* plan_button_;
  QPushButton* execute_button_;
  QPushButton* plan_execute_button_;
  QPushButton* stop_button_;
  QLabel* status_label_;

  std::shared_ptr<const SemanticModel> model_;
  std::unique_ptr<PlanningPanelLogic> logic_;
  QString saved_group_;
  QString saved_named_state_;
};

}  // namespace sixdof_rviz
